// libFuzzer target: the MAVLink v2 receiver (firmware/protocol/mavlink_receiver) and the TIMESYNC
// reader on arbitrary RX bytes. Every frame it passes on is a TIMESYNC whose payload fits the
// message, and reading it never fails.
#include <cstdint>
#include <cstdlib>

#include "firmware/protocol/mavlink_messages.hpp"
#include "firmware/protocol/mavlink_receiver.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  irloc::firmware::MavlinkReceiver receiver;
  for (std::size_t i = 0; i < size; ++i) {
    const auto frame = receiver.push(data[i]);
    if (!frame) continue;
    if (frame->message_id != irloc::firmware::Timesync::kId || frame->payload.size() > irloc::firmware::Timesync::kPayloadSize) {
      std::abort();
    }
    const irloc::firmware::Timesync timesync = irloc::firmware::read_timesync(frame->payload);
    static_cast<void>(timesync);
  }
  return 0;
}
