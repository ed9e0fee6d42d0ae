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
  void put(std::uint64_t value) {
    for (int i = 0; i < 8; ++i) put(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  void put(float value) { put(std::bit_cast<std::uint32_t>(value)); }

  std::size_t size() const { return at_; }

 private:
  std::span<std::uint8_t> out_;
  std::size_t at_ = 0;
};

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

}  // namespace irloc::firmware
