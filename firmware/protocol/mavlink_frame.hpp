#pragma once
// MAVLink v2 framing (https://mavlink.io/en/guide/serialization.html), written out by hand
// because the pose stream is the product: header, payload with trailing zeros truncated, and the
// CRC-16/MCRF4XX checksum seeded with the message's CRC_EXTRA. Unsigned frames only.

#include <cstddef>
#include <cstdint>
#include <span>

namespace irloc::firmware {

constexpr std::uint8_t kMavlink2Magic = 0xFD;
constexpr std::size_t kMavlink2HeaderSize = 10;  // magic .. msgid
constexpr std::size_t kMavlink2ChecksumSize = 2;
constexpr std::size_t kMavlinkMaxPayload = 255;
constexpr std::size_t kMavlink2MaxFrame = kMavlink2HeaderSize + kMavlinkMaxPayload + kMavlink2ChecksumSize;

// CRC-16/MCRF4XX (the "X.25" CRC of MAVLink): poly 0x1021 reflected, init 0xFFFF, no final xor.
class MavlinkCrc {
 public:
  void add(std::uint8_t byte);
  void add(std::span<const std::uint8_t> bytes);
  std::uint16_t value() const { return crc_; }

 private:
  std::uint16_t crc_ = 0xFFFF;
};

struct MavlinkAddress {
  std::uint8_t system_id = 1;
  std::uint8_t component_id = 197;  // MAV_COMP_ID_VISUAL_INERTIAL_ODOMETRY
};

// Writes one frame into `out` and returns its length, or 0 when `out` is too small or the payload
// is longer than 255 bytes. `payload` is the message's full wire payload (fields in MAVLink wire
// order, extensions included); trailing zero bytes are dropped as MAVLink v2 requires (at least
// one byte stays). Allocates nothing.
std::size_t encode_mavlink2(std::span<std::uint8_t> out, const MavlinkAddress& address, std::uint8_t sequence,
                            std::uint32_t message_id, std::uint8_t crc_extra, std::span<const std::uint8_t> payload);

}  // namespace irloc::firmware
