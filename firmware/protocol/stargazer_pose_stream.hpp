#pragma once
// StarGazer-compatible ASCII results (docs/hardware.md, "StarGazer ASCII"), so a robot built
// around that discontinued ceiling sensor's map mode reads irloc unchanged:
//   ~^I<id>|<angle>|<x>|<y>|<height>`     one good pose
//   ~*DeadZone`                          no pose
// angle: yaw in degrees, sign always written, 2 decimals, in (-180, 180]; x, y: W position in
// centimetres, sign always written, 2 decimals; height: landmark height above the camera in
// centimetres, 2 decimals, no sign; id: the dot marker's ID, 0 for other landmark kinds.
// No line terminator: the back-quote ends a message, as on the original sensor. The host commands
// a driver sends (stargazer_host_commands.hpp) are answered; between CalcStop and CalcStart no
// result is sent; with HeightFix Yes the height is the written MarkHeight.

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "algo/map/marker_map.hpp"
#include "firmware/protocol/pose_stream_encoder.hpp"
#include "firmware/protocol/stargazer_host_commands.hpp"

namespace irloc::firmware {

class StarGazerPoseStream final : public PoseStreamEncoder {
 public:
  // `camera_height_m`: the camera's height above the base origin (the mount's z). Landmark
  // heights come from `map`: the marker's own height for a dot marker, else the mean height of
  // every landmark in the map. `version` and `baud_rate` answer the Version and BaudRate reads.
  StarGazerPoseStream(const MarkerMap& map, double camera_height_m, std::string_view version, int baud_rate);

  std::span<const std::uint8_t> encode(const PoseEstimate& estimate) override;
  std::span<const std::uint8_t> receive(std::span<const std::uint8_t> bytes, std::int64_t now_ns) override;
  std::string_view receive_note() const override { return commands_.last_refusal(); }
  const StarGazerHostCommands& host_commands() const { return commands_; }

 private:
  double landmark_z(int marker_id) const;

  std::vector<std::pair<int, double>> dot_marker_z_;  // filled at start-up, read per frame
  double mean_landmark_z_ = 0;
  double camera_height_m_;
  StarGazerHostCommands commands_;
  std::array<char, 96> buffer_{};
};

}  // namespace irloc::firmware
