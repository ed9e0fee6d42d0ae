#include "firmware/protocol/mavlink_frame.hpp"

namespace irloc::firmware {

void MavlinkCrc::add(std::uint8_t byte) {
  std::uint8_t tmp = byte ^ static_cast<std::uint8_t>(crc_ & 0xFF);
  tmp ^= static_cast<std::uint8_t>(tmp << 4);
  crc_ = static_cast<std::uint16_t>((crc_ >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
}

void MavlinkCrc::add(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t byte : bytes) add(byte);
}

std::size_t encode_mavlink2(std::span<std::uint8_t> out, const MavlinkAddress& address, std::uint8_t sequence,
                            std::uint32_t message_id, std::uint8_t crc_extra, std::span<const std::uint8_t> payload) {
  if (payload.size() > kMavlinkMaxPayload) return 0;
  std::size_t length = payload.size();
  while (length > 1 && payload[length - 1] == 0) --length;
  const std::size_t frame_size = kMavlink2HeaderSize + length + kMavlink2ChecksumSize;
  if (out.size() < frame_size) return 0;

  out[0] = kMavlink2Magic;
  out[1] = static_cast<std::uint8_t>(length);
  out[2] = 0;  // incompat_flags: not signed
  out[3] = 0;  // compat_flags
  out[4] = sequence;
  out[5] = address.system_id;
  out[6] = address.component_id;
  out[7] = static_cast<std::uint8_t>(message_id & 0xFF);
  out[8] = static_cast<std::uint8_t>((message_id >> 8) & 0xFF);
  out[9] = static_cast<std::uint8_t>((message_id >> 16) & 0xFF);
  for (std::size_t i = 0; i < length; ++i) out[kMavlink2HeaderSize + i] = payload[i];

  MavlinkCrc crc;
  crc.add(out.subspan(1, kMavlink2HeaderSize - 1 + length));
  crc.add(crc_extra);
  out[kMavlink2HeaderSize + length] = static_cast<std::uint8_t>(crc.value() & 0xFF);
  out[kMavlink2HeaderSize + length + 1] = static_cast<std::uint8_t>(crc.value() >> 8);
  return frame_size;
}

}  // namespace irloc::firmware
