#pragma once
// The MAVLink v2 pose stream for an autopilot's external navigation (ArduPilot ExternalNav,
// VISO_TYPE = MAVLink): a VISION_POSITION_ESTIMATE per good pose, in NED (ned_frame.hpp), and a
// HEARTBEAT once per second of frame time. Nothing is sent for a failed attempt: the autopilot
// sees the gap and falls back to its other sources.
//
// The message's covariance is the pose's own (its source's solver at the solution: anisotropic,
// with the cross terms), in NED, plus an isotropic floor for what that model cannot see
// (calibration and map errors): position_floor_m^2 on x, y, z and angle_floor_rad^2 on the angles.

#include <array>
#include <cstdint>
#include <optional>

#include "firmware/protocol/mavlink_frame.hpp"
#include "firmware/protocol/pose_stream_encoder.hpp"

namespace irloc::firmware {

struct MavlinkStreamSettings {
  MavlinkAddress address;
  double position_floor_m = 0.02;     // 1-sigma added in quadrature to every position variance
  double angle_floor_rad = 0.02;      // and to every angle variance
  double reset_jump_m = 0.5;          // a jump this large between good poses is a relocalization
  double reset_after_loss_s = 1.0;    // so is the first good pose after this long without one
  // The poses are in a frame that never jumps (outside-in: the floor reference ties every wall
  // camera to the room): reset_counter stays 0. ArduPilot (one AP_VisualOdom backend, one last
  // reset counter) and PX4 (one vehicle_visual_odometry topic) take VISION_POSITION_ESTIMATE from
  // every component ID as one source, so several cameras feeding one vehicle must agree on the
  // counter; a counter each bumped on its own losses would read as a reset at every hand-over.
  bool fixed_frame = false;
  std::int64_t heartbeat_period_ns = 1'000'000'000;
};

class MavlinkPoseStream final : public PoseStreamEncoder {
 public:
  explicit MavlinkPoseStream(const MavlinkStreamSettings& settings) : settings_(settings) {}

  std::span<const std::uint8_t> encode(const PoseEstimate& estimate) override;

  std::uint8_t reset_counter() const { return reset_counter_; }

 private:
  void append_heartbeat();
  void append_vision_position(const PoseEstimate& estimate);
  void update_reset_counter(const PoseEstimate& estimate);

  MavlinkStreamSettings settings_;
  std::array<std::uint8_t, 2 * kMavlink2MaxFrame> buffer_{};
  std::size_t used_ = 0;
  std::uint8_t sequence_ = 0;
  std::uint8_t reset_counter_ = 0;
  std::optional<std::int64_t> last_heartbeat_ns_;
  std::optional<PoseEstimate> last_good_;
};

}  // namespace irloc::firmware
