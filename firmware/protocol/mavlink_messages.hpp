#pragma once
// The two MAVLink messages irlocd sends, as plain structs, and their wire payloads (fields in
// MAVLink wire order: by decreasing type size, extensions last, little-endian).

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

// Each writes the full (untruncated) payload and returns it as a view of `out`.
std::span<const std::uint8_t> write_payload(const Heartbeat& message, std::array<std::uint8_t, Heartbeat::kPayloadSize>& out);
std::span<const std::uint8_t> write_payload(const VisionPositionEstimate& message,
                                            std::array<std::uint8_t, VisionPositionEstimate::kPayloadSize>& out);

}  // namespace irloc::firmware
