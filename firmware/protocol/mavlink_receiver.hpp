#pragma once
// The MAVLink v2 frames in a received byte stream (split anywhere, with noise between frames):
// each frame of a message irlocd reads (TIMESYNC) whose checksum is right, with its sender.
// Frames of other messages, and frames that fail their checksum, are skipped. Signed frames are
// taken without checking the signature. Allocates nothing.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "firmware/protocol/mavlink_frame.hpp"

namespace irloc::firmware {

struct ReceivedMavlinkFrame {
  std::uint8_t system_id = 0;
  std::uint8_t component_id = 0;
  std::uint32_t message_id = 0;
  std::span<const std::uint8_t> payload;  // as received (trailing zeros truncated); valid until the next push
};

class MavlinkReceiver {
 public:
  // One received byte; a frame when this byte completes one.
  std::optional<ReceivedMavlinkFrame> push(std::uint8_t byte);

  std::uint64_t checksum_errors() const { return checksum_errors_; }

 private:
  static constexpr std::size_t kSignatureSize = 13;
  std::optional<ReceivedMavlinkFrame> complete();

  std::array<std::uint8_t, kMavlink2MaxFrame + kSignatureSize> frame_{};
  std::size_t size_ = 0;
  std::uint64_t checksum_errors_ = 0;
};

}  // namespace irloc::firmware
