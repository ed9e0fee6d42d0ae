#pragma once
// The MAVLink v2 pose stream for an autopilot's external navigation (ArduPilot ExternalNav,
// VISO_TYPE = MAVLink; PX4 EKF2 external vision): a VISION_POSITION_ESTIMATE per good pose, in NED
// (ned_frame.hpp), or, when configured, an ODOMETRY: the same pose (frame LOCAL_FRD, the NED frame
// above) with the track's velocity in the body frame FRD (NaN when the track has none). Nothing is sent for a failed attempt: the autopilot sees the gap and falls back
// to its other sources. On the link's own clock, whatever the camera does: a HEARTBEAT every
// second whose system_status tells the link's health (STANDBY while starting, ACTIVE, CRITICAL),
// and, when configured, SET_GPS_GLOBAL_ORIGIN with the first heartbeat and every tenth after it.
// A STATUSTEXT (severity WARNING) for each warning irlocd prints; a TIMESYNC request is answered
// with the time of its arrival on CLOCK_MONOTONIC, the clock of `usec`, so that PX4 can use the
// capture time.
//
// The message's covariance is the pose's own (its source's solver at the solution: anisotropic,
// with the cross terms), in NED, plus an isotropic floor for what that model cannot see
// (calibration and map errors): position_floor_m^2 on x, y, z and angle_floor_rad^2 on the angles.

#include <array>
#include <cstdint>
#include <optional>

#include "firmware/protocol/mavlink_frame.hpp"
#include "firmware/protocol/mavlink_receiver.hpp"
#include "firmware/protocol/pose_stream_encoder.hpp"

namespace irloc::firmware {

// The EKF origin for a vehicle without GPS (WGS84 degrees, metres above mean sea level).
struct GeoOrigin {
  double latitude_deg = 0;
  double longitude_deg = 0;
  double altitude_m = 0;
};

// The message that carries each good pose.
enum class MavlinkPoseMessage { vision_position_estimate, odometry };

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
  std::optional<GeoOrigin> ekf_origin;
  MavlinkPoseMessage pose_message = MavlinkPoseMessage::vision_position_estimate;
};

class MavlinkPoseStream final : public PoseStreamEncoder {
 public:
  explicit MavlinkPoseStream(const MavlinkStreamSettings& settings) : settings_(settings) {}

  std::span<const std::uint8_t> encode(const PoseEstimate& estimate) override;
  std::span<const std::uint8_t> tick(std::int64_t now_ns) override;
  std::span<const std::uint8_t> receive(std::span<const std::uint8_t> bytes, std::int64_t now_ns) override;
  std::span<const std::uint8_t> warning(std::string_view text) override;
  void set_health(LinkHealth health) override { health_ = health; }

  std::uint8_t reset_counter() const { return reset_counter_; }

 private:
  // Frames appended to buffer_ until it is full: one call's messages, at most 6 frames.
  template <typename Message>
  void append(const Message& message);
  void append_heartbeat();
  void append_origin(std::int64_t now_ns);
  void append_vision_position(const PoseEstimate& estimate);
  void append_odometry(const PoseEstimate& estimate);
  // The pose's covariance in NED with the floors added, as MAVLink's upper-right triangle.
  std::array<float, 21> pose_covariance(const PoseEstimate& estimate) const;
  void update_reset_counter(const PoseEstimate& estimate);

  MavlinkStreamSettings settings_;
  std::array<std::uint8_t, 6 * kMavlink2MaxFrame> buffer_{};
  std::size_t used_ = 0;
  std::uint8_t sequence_ = 0;
  std::uint8_t reset_counter_ = 0;
  LinkHealth health_ = LinkHealth::starting;
  std::optional<std::int64_t> last_heartbeat_ns_;
  std::uint64_t heartbeats_ = 0;
  std::uint16_t last_text_id_ = 0;
  MavlinkReceiver receiver_;
  std::optional<PoseEstimate> last_good_;
};

}  // namespace irloc::firmware
