#pragma once
// The serial pose-stream output: whole messages in, never a stall. A reader that is slow or
// absent costs messages (dropped whole and counted), never the pipeline's time, and never a
// torn message on the line.

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
};

}  // namespace irloc::hal
