#pragma once
// StarGazer-compatible ASCII results (docs/hardware.md, "StarGazer ASCII"), so a robot built
// around that discontinued ceiling sensor's map mode reads irloc unchanged:
//   ~^I<id>|<angle>|<x>|<y>|<height>`     one good pose
//   ~*DeadZone`                          no pose
// angle: yaw in degrees, sign always written, 2 decimals, in (-180, 180]; x, y: W position in
// centimetres, sign always written, 2 decimals; height: landmark height above the camera in
// centimetres, 2 decimals, no sign; id: the dot marker's ID, 0 for other landmark kinds.
// No line terminator: the back-quote ends a message, as on the original sensor.

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "algo/map/marker_map.hpp"
#include "firmware/protocol/pose_stream_encoder.hpp"

namespace irloc::firmware {

class StarGazerPoseStream final : public PoseStreamEncoder {
 public:
  // `camera_height_m`: the camera's height above the base origin (the mount's z). Landmark
  // heights come from `map`: the marker's own height for a dot marker, else the mean height of
  // every landmark in the map.
  StarGazerPoseStream(const MarkerMap& map, double camera_height_m);

  std::span<const std::uint8_t> encode(const PoseEstimate& estimate) override;

 private:
  double landmark_z(int marker_id) const;

  std::vector<std::pair<int, double>> dot_marker_z_;  // filled at start-up, read per frame
  double mean_landmark_z_ = 0;
  double camera_height_m_;
  std::array<char, 96> buffer_{};
};

}  // namespace irloc::firmware
