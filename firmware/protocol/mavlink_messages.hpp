#pragma once
// The MAVLink messages irlocd sends and reads, as plain structs, and their wire payloads (fields
// in MAVLink wire order: by decreasing type size, extensions last, little-endian).

#include <array>
#include <cstdint>
#include <span>

namespace irloc::firmware {

// HEARTBEAT (#0) of common.xml/minimal.xml.
struct Heartbeat {
  static constexpr std::uint32_t kId = 0;
  static constexpr std::uint8_t kCrcExtra = 50;
  static constexpr std::size_t kPayloadSize = 9;

  std::uint32_t custom_mode = 0;
  std::uint8_t type = 18;           // MAV_TYPE_ONBOARD_CONTROLLER
  std::uint8_t autopilot = 8;       // MAV_AUTOPILOT_INVALID: not an autopilot
  std::uint8_t base_mode = 0;
  std::uint8_t system_status = 4;   // MAV_STATE_ACTIVE
  std::uint8_t mavlink_version = 3;
};

// VISION_POSITION_ESTIMATE (#102): a local NED position (metres) and attitude (radians) with the
// extensions covariance (upper-right triangle of the 6x6 x,y,z,roll,pitch,yaw matrix, row-major;
// NaN in the first element when unknown) and reset_counter (bumped when the estimate jumps).
struct VisionPositionEstimate {
  static constexpr std::uint32_t kId = 102;
  static constexpr std::uint8_t kCrcExtra = 158;
  static constexpr std::size_t kPayloadSize = 117;

  std::uint64_t usec = 0;  // timestamp, microseconds since boot (or UNIX epoch)
  float x = 0, y = 0, z = 0;
  float roll = 0, pitch = 0, yaw = 0;
  std::array<float, 21> covariance{};
  std::uint8_t reset_counter = 0;
};

// ODOMETRY (#331): the pose (position in frame_id, attitude as the quaternion w, x, y, z of R_frame_body)
// and the velocity (in child_frame_id), each with the upper-right triangle of its 6x6 covariance
// (NaN in the first element when unknown); NaN in a field that is not measured.
struct Odometry {
  static constexpr std::uint32_t kId = 331;
  static constexpr std::uint8_t kCrcExtra = 91;
  static constexpr std::size_t kPayloadSize = 233;
  static constexpr std::uint8_t kFrameLocalFrd = 20;      // MAV_FRAME_LOCAL_FRD
  static constexpr std::uint8_t kFrameBodyFrd = 12;       // MAV_FRAME_BODY_FRD
  static constexpr std::uint8_t kEstimatorVision = 3;     // MAV_ESTIMATOR_TYPE_VISION

  std::uint64_t time_usec = 0;
  float x = 0, y = 0, z = 0;
  std::array<float, 4> q{1, 0, 0, 0};
  float vx = 0, vy = 0, vz = 0;
  float rollspeed = 0, pitchspeed = 0, yawspeed = 0;
  std::array<float, 21> pose_covariance{};
  std::array<float, 21> velocity_covariance{};
  std::uint8_t frame_id = kFrameLocalFrd;
  std::uint8_t child_frame_id = kFrameBodyFrd;
  std::uint8_t reset_counter = 0;
  std::uint8_t estimator_type = kEstimatorVision;
  std::int8_t quality = 0;  // percent; 0 unknown
};

// STATUSTEXT (#253): a text of up to 50 characters (NUL-padded; no NUL when all 50 are used);
// a longer text goes out in chunks sharing a non-zero `id`, `chunk_seq` counting from 0.
struct StatusText {
  static constexpr std::uint32_t kId = 253;
  static constexpr std::uint8_t kCrcExtra = 83;
  static constexpr std::size_t kPayloadSize = 54;
  static constexpr std::size_t kTextSize = 50;

  std::uint8_t severity = 4;  // MAV_SEVERITY_WARNING
  std::array<char, kTextSize> text{};
  std::uint16_t id = 0;
  std::uint8_t chunk_seq = 0;
};

// TIMESYNC (#111): a request has tc1 = 0 and the sender's time in ts1 (ns); the answer carries the
// receiver's time in tc1 and the request's ts1 unchanged.
struct Timesync {
  static constexpr std::uint32_t kId = 111;
  static constexpr std::uint8_t kCrcExtra = 34;
  static constexpr std::size_t kPayloadSize = 18;

  std::int64_t tc1 = 0;
  std::int64_t ts1 = 0;
  std::uint8_t target_system = 0;
  std::uint8_t target_component = 0;
};

// SET_GPS_GLOBAL_ORIGIN (#48): the EKF origin of a vehicle without GPS. Degrees * 1e7, mm above MSL.
struct SetGpsGlobalOrigin {
  static constexpr std::uint32_t kId = 48;
  static constexpr std::uint8_t kCrcExtra = 41;
  static constexpr std::size_t kPayloadSize = 21;

  std::int32_t latitude = 0;
  std::int32_t longitude = 0;
  std::int32_t altitude = 0;
  std::uint8_t target_system = 0;  // 0: every system
  std::uint64_t time_usec = 0;
};

// Each writes the full (untruncated) payload and returns it as a view of `out`.
std::span<const std::uint8_t> write_payload(const Heartbeat& message, std::array<std::uint8_t, Heartbeat::kPayloadSize>& out);
std::span<const std::uint8_t> write_payload(const VisionPositionEstimate& message,
                                            std::array<std::uint8_t, VisionPositionEstimate::kPayloadSize>& out);
std::span<const std::uint8_t> write_payload(const Odometry& message, std::array<std::uint8_t, Odometry::kPayloadSize>& out);
std::span<const std::uint8_t> write_payload(const StatusText& message, std::array<std::uint8_t, StatusText::kPayloadSize>& out);
std::span<const std::uint8_t> write_payload(const Timesync& message, std::array<std::uint8_t, Timesync::kPayloadSize>& out);
std::span<const std::uint8_t> write_payload(const SetGpsGlobalOrigin& message,
                                            std::array<std::uint8_t, SetGpsGlobalOrigin::kPayloadSize>& out);

// A TIMESYNC from a received payload (MAVLink v2 truncates trailing zeros: missing bytes are 0).
Timesync read_timesync(std::span<const std::uint8_t> payload);

}  // namespace irloc::firmware
