#include "firmware/protocol/mavlink_receiver.hpp"

#include "firmware/protocol/mavlink_messages.hpp"

namespace irloc::firmware {
namespace {

// The CRC_EXTRA of the messages irlocd reads; none for the others.
std::optional<std::uint8_t> crc_extra_of(std::uint32_t message_id) {
  if (message_id == Timesync::kId) return Timesync::kCrcExtra;
  return std::nullopt;
}

}  // namespace

std::optional<ReceivedMavlinkFrame> MavlinkReceiver::push(std::uint8_t byte) {
  if (size_ == 0 && byte != kMavlink2Magic) return std::nullopt;
  frame_[size_++] = byte;
  if (size_ < kMavlink2HeaderSize) return std::nullopt;
  const bool signed_frame = (frame_[2] & 0x01) != 0;
  const std::size_t total = kMavlink2HeaderSize + frame_[1] + kMavlink2ChecksumSize + (signed_frame ? kSignatureSize : 0);
  if (size_ < total) return std::nullopt;
  size_ = 0;
  return complete();
}

std::optional<ReceivedMavlinkFrame> MavlinkReceiver::complete() {
  const std::size_t length = frame_[1];
  ReceivedMavlinkFrame frame;
  frame.system_id = frame_[5];
  frame.component_id = frame_[6];
  frame.message_id = static_cast<std::uint32_t>(frame_[7] | frame_[8] << 8 | frame_[9] << 16);
  const std::optional<std::uint8_t> crc_extra = crc_extra_of(frame.message_id);
  if (!crc_extra) return std::nullopt;
  MavlinkCrc crc;
  crc.add(std::span<const std::uint8_t>(frame_).subspan(1, kMavlink2HeaderSize - 1 + length));
  crc.add(*crc_extra);
  const std::uint16_t sent = static_cast<std::uint16_t>(frame_[kMavlink2HeaderSize + length] |
                                                        frame_[kMavlink2HeaderSize + length + 1] << 8);
  if (sent != crc.value()) {
    ++checksum_errors_;
    return std::nullopt;
  }
  frame.payload = std::span<const std::uint8_t>(frame_).subspan(kMavlink2HeaderSize, length);
  return frame;
}

}  // namespace irloc::firmware
