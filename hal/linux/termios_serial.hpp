#pragma once
// A serial device (UART, USB serial, pseudo-terminal) in raw 8N1 mode at a fixed baud rate, written
// without blocking through a queue of whole messages (hal/serial_port.hpp). A device that goes away
// while running (a write fails with anything but "full") is closed, its queue dropped, and opened
// again by path at most every 0.5 s from write_message; meanwhile messages are dropped whole.
// What the far end sends is read without blocking (read_received).

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "hal/serial_port.hpp"

namespace irloc::hal {

class TermiosSerial final : public SerialPort {
 public:
  // Opens `path` non-blocking, sets raw mode (no echo, no line editing, no CR/LF translation, no
  // flow control, 8 data bits, no parity, 1 stop bit) at `baud`, and sizes the queue to
  // `queue_bytes`. Throws io::InputError "serial PATH: problem" for a missing device, a device that
  // is not a terminal, or an unsupported baud rate.
  TermiosSerial(const std::string& path, int baud, std::size_t queue_bytes = 4096);
  ~TermiosSerial() override;
  TermiosSerial(const TermiosSerial&) = delete;
  TermiosSerial& operator=(const TermiosSerial&) = delete;

  bool write_message(std::span<const std::uint8_t> message) override;
  std::uint64_t messages_sent() const override { return sent_; }
  std::uint64_t messages_dropped() const override { return dropped_; }
  bool connected() const override { return fd_ >= 0; }
  std::uint64_t losses() const override { return losses_; }
  int last_error() const override { return last_error_; }
  void reopen_now() override;
  int receive_fd() const override { return fd_; }
  // A read error other than "nothing yet" means the device is gone, as for a write.
  std::size_t read_received(std::span<std::uint8_t> out) override;

  // Bytes queued but not yet taken by the device.
  std::size_t queued_bytes() const { return size_; }
  // Sends what the device takes now; irlocd calls it through write_message only.
  void flush();

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr Clock::duration kReopenInterval = std::chrono::milliseconds(500);

  void lose(int error);
  bool try_reopen();

  int fd_ = -1;
  int baud_ = 0;
  std::uint64_t losses_ = 0;
  int last_error_ = 0;
  Clock::time_point next_attempt_{};
  std::string path_;
  std::vector<std::uint8_t> queue_;  // ring buffer, sized once
  std::size_t head_ = 0;             // first queued byte
  std::size_t size_ = 0;
  std::uint64_t sent_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace irloc::hal
