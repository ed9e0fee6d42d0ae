#pragma once
// Reads the irloc config YAML and the calibration and map files it names (docs/formats.md).

#include <cstdint>
#include <filesystem>
#include <optional>

#include "algo/calibration/mount_tilt_watch.hpp"
#include "algo/pipeline/localizer_setup.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

// `mode`: the camera rides on the robot, or a fixed camera watches it (docs/outside_in.md).
enum class RobotMode { on_robot, outside_in };

// The EKF origin a MAVLink autopilot without GPS is given (SET_GPS_GLOBAL_ORIGIN): WGS84
// degrees and metres above mean sea level.
struct EkfOrigin {
  double latitude_deg = 0;
  double longitude_deg = 0;
  double altitude_m = 0;
};

struct RobotConfig {
  RobotMode mode = RobotMode::on_robot;
  std::filesystem::path calibration_file;  // resolved against the config file's folder
  std::filesystem::path map_file;          // empty: none (optional in outside-in mode)
  LocalizerSetup setup;
  // The online watch of the mount's tilt: on by default for dof 3 and 4, off for dof 6 and in
  // outside-in mode.
  calibration::MountWatchConfig mount_watch;
  std::optional<EkfOrigin> ekf_origin;  // `mavlink.ekf_origin`
  bool odometry = false;                // `mavlink.pose_message: odometry` (else vision_position_estimate)
};

// Throws InputError naming the file (the config, the calibration or the map), line and field
// of the first problem.
RobotConfig load_robot_config(const std::filesystem::path& path);
// The same for a config already parsed (`root`: the whole file).
RobotConfig read_robot_config(YamlMap& root);

// `robot.max_speed` and `robot.max_yaw_rate` (both modes): the fastest robot, for the rolling
// shutter (algo/source/source_input.hpp).
std::span<const Setting<MotionLimits>> robot_motion_settings();

// Those keys and the optional `robot.max_side_speed` (at most max_speed; absent: max_speed) into
// limits; the rest of `robot` is the caller's.
void read_robot_motion(YamlMap& robot, MotionLimits& limits);

// The optional `max_side_speed` of a robot mapping (config, scenario), range-checked; the check
// against max_speed is read_robot_motion's.
std::optional<double> read_side_speed(YamlMap& robot);

// The optional `line_time_ns` of a camera mapping (config, board file, scenario): row r exposed
// r * line_time_ns after row 0 (conventions.md); absent or 0: a global shutter.
std::int64_t read_line_time(YamlMap& camera);

// T_B_C from a `camera.mount` mapping (docs/conventions.md), checked strictly.
RigidTransform read_mount(YamlMap& mount);

}  // namespace irloc::io
