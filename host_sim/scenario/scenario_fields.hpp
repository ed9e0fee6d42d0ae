#pragma once
// The readers that the scenario's sections share (docs/formats.md's scenario): value ranges,
// points, the camera's calibration and rolling shutter, the trajectory and the people.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "host_sim/scenario/scenario.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::sim {

// Ranges of docs/formats.md.
inline constexpr io::Range kWorldCoordinate{-10'000, 10'000};  // metres
inline constexpr io::Range kAngle{-7, 7};                      // radians, within a turn either way
inline constexpr io::Range kDirection{-1'000, 1'000};          // a direction vector's components
inline constexpr io::Range kRigOffset{-10, 10};                // metres from the camera
inline constexpr io::Range kSize{1e-3, 1'000};                 // metres
inline constexpr io::Range kSpeed{1e-3, 100};                  // m/s or rad/s
inline constexpr io::Range kRadiance{0, 1e9};                  // W sr^-1 m^-2, W/m^2
inline constexpr io::Range kIntensity{1e-9, 1e6};              // W/sr
inline constexpr io::Range kFraction{0, 1};
// Clutter sizes: from a sticker to a duct's length; below a millimetre it would render as nothing.
inline constexpr io::Range kStripLength{0.005, 20};  // metres
inline constexpr io::Range kStripWidth{0.002, 1};    // metres
inline constexpr io::Range kCrescentRadius{0.002, 1};  // metres


// [x0, y0, x1, y1] with x1 > x0 and y1 > y0.
Eigen::Vector4d read_rectangle(io::YamlMap& map, const std::string& key);
// A list of [x, y] world points.
std::vector<Eigen::Vector2d> read_points2(io::YamlMap& map, const std::string& key);
// The camera's `line_time_ns` (a rolling shutter; 0: global), whose rows must be read out within
// one frame period.
std::int64_t read_rolling_shutter(io::YamlMap& camera, int height, double frame_rate);
// Exactly one of `calibration` (camera_info keys inline) and `calibration_file` (relative to
// `base_dir`; `file` is set to it).
CameraIntrinsics read_camera_calibration(io::YamlMap& camera, const std::filesystem::path& base_dir,
                                         std::filesystem::path& file);
TrajectorySpec read_trajectory(io::YamlMap& map);
std::vector<Occluder> read_people(io::YamlMap& root);

}  // namespace irloc::sim
