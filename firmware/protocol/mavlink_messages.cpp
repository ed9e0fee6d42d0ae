#include "firmware/protocol/mavlink_messages.hpp"

#include <bit>

namespace irloc::firmware {
namespace {

// Little-endian writer over a fixed buffer; every message's size is known at compile time.
class PayloadWriter {
 public:
  explicit PayloadWriter(std::span<std::uint8_t> out) : out_(out) {}

  void put(std::uint8_t value) { out_[at_++] = value; }
  void put(std::uint32_t value) {
    for (int i = 0; i < 4; ++i) put(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void put(std::uint16_t value) {
    for (int i = 0; i < 2; ++i) put(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void put(std::uint64_t value) {
    for (int i = 0; i < 8; ++i) put(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void put(float value) { put(std::bit_cast<std::uint32_t>(value)); }
  void put(std::int32_t value) { put(std::bit_cast<std::uint32_t>(value)); }
  void put(std::int64_t value) { put(std::bit_cast<std::uint64_t>(value)); }

  std::size_t size() const { return at_; }

 private:
  std::span<std::uint8_t> out_;
  std::size_t at_ = 0;
};

std::uint64_t read_little_endian(std::span<const std::uint8_t> payload, std::size_t at, std::size_t size) {
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < size; ++i) {
    if (at + i < payload.size()) value |= static_cast<std::uint64_t>(payload[at + i]) << (8 * i);
  }
  return value;
}

}  // namespace

std::span<const std::uint8_t> write_payload(const Heartbeat& message, std::array<std::uint8_t, Heartbeat::kPayloadSize>& out) {
  PayloadWriter writer(out);
  writer.put(message.custom_mode);
  writer.put(message.type);
  writer.put(message.autopilot);
  writer.put(message.base_mode);
  writer.put(message.system_status);
  writer.put(message.mavlink_version);
  return {out.data(), writer.size()};
}

std::span<const std::uint8_t> write_payload(const VisionPositionEstimate& message,
                                            std::array<std::uint8_t, VisionPositionEstimate::kPayloadSize>& out) {
  PayloadWriter writer(out);
  writer.put(message.usec);
  for (const float value : {message.x, message.y, message.z, message.roll, message.pitch, message.yaw}) writer.put(value);
  for (const float value : message.covariance) writer.put(value);
  writer.put(message.reset_counter);
  return {out.data(), writer.size()};
}

std::span<const std::uint8_t> write_payload(const Odometry& message, std::array<std::uint8_t, Odometry::kPayloadSize>& out) {
  PayloadWriter writer(out);
  writer.put(message.time_usec);
  for (const float value : {message.x, message.y, message.z}) writer.put(value);
  for (const float value : message.q) writer.put(value);
  for (const float value : {message.vx, message.vy, message.vz, message.rollspeed, message.pitchspeed, message.yawspeed}) {
    writer.put(value);
  }
  for (const float value : message.pose_covariance) writer.put(value);
  for (const float value : message.velocity_covariance) writer.put(value);
  writer.put(message.frame_id);
  writer.put(message.child_frame_id);
  writer.put(message.reset_counter);
  writer.put(message.estimator_type);
  writer.put(static_cast<std::uint8_t>(message.quality));
  return {out.data(), writer.size()};
}

std::span<const std::uint8_t> write_payload(const StatusText& message, std::array<std::uint8_t, StatusText::kPayloadSize>& out) {
  PayloadWriter writer(out);
  writer.put(message.severity);
  for (const char c : message.text) writer.put(static_cast<std::uint8_t>(c));
  writer.put(message.id);
  writer.put(message.chunk_seq);
  return {out.data(), writer.size()};
}

std::span<const std::uint8_t> write_payload(const Timesync& message, std::array<std::uint8_t, Timesync::kPayloadSize>& out) {
  PayloadWriter writer(out);
  writer.put(message.tc1);
  writer.put(message.ts1);
  writer.put(message.target_system);
  writer.put(message.target_component);
  return {out.data(), writer.size()};
}

std::span<const std::uint8_t> write_payload(const SetGpsGlobalOrigin& message,
                                            std::array<std::uint8_t, SetGpsGlobalOrigin::kPayloadSize>& out) {
  PayloadWriter writer(out);
  writer.put(message.latitude);
  writer.put(message.longitude);
  writer.put(message.altitude);
  writer.put(message.target_system);
  writer.put(message.time_usec);
  return {out.data(), writer.size()};
}

Timesync read_timesync(std::span<const std::uint8_t> payload) {
  Timesync message;
  message.tc1 = std::bit_cast<std::int64_t>(read_little_endian(payload, 0, 8));
  message.ts1 = std::bit_cast<std::int64_t>(read_little_endian(payload, 8, 8));
  message.target_system = static_cast<std::uint8_t>(read_little_endian(payload, 16, 1));
  message.target_component = static_cast<std::uint8_t>(read_little_endian(payload, 17, 1));
  return message;
}

}  // namespace irloc::firmware
