#pragma once
// The serial pose-stream link: whole messages out, never a stall, and the bytes the far end sends
// back (a host driver's commands, an autopilot's TIMESYNC). A reader that is slow or absent costs
// messages (dropped whole and counted), never the pipeline's time, and never a torn message on the line.

#include <cstddef>
#include <cstdint>
#include <span>

namespace irloc::hal {

class SerialPort {
 public:
  virtual ~SerialPort() = default;

  // Queues the whole message and sends what the device takes now, without blocking. Returns
  // false, and counts the message as dropped, when it does not fit in the queue. Allocates nothing.
  virtual bool write_message(std::span<const std::uint8_t> message) = 0;

  virtual std::uint64_t messages_sent() const = 0;     // queued whole
  virtual std::uint64_t messages_dropped() const = 0;  // not sent at all

  // A device that can go away (a USB serial adapter): whether it is there now, how often it was
  // lost, the errno of the last loss, and closing and opening it again at once (SIGHUP).
  virtual bool connected() const { return true; }
  virtual std::uint64_t losses() const { return 0; }
  virtual int last_error() const { return 0; }
  virtual void reopen_now() {}

  // Receiving: the descriptor to poll(2) for input (-1: none now, or a link that only sends), and
  // the bytes that have arrived, up to out.size(), without blocking (0 when none). Allocates nothing.
  virtual int receive_fd() const { return -1; }
  virtual std::size_t read_received(std::span<std::uint8_t> /*out*/) { return 0; }
};

}  // namespace irloc::hal
