#include "hal/linux/termios_serial.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iterator>

#include "io/input_error.hpp"
#include "hal/serial_bauds.hpp"

namespace irloc::hal {
namespace {

struct BaudConstant {
  int baud;
  speed_t constant;
};

constexpr BaudConstant kBauds[] = {
    {9600, B9600},       {19200, B19200},     {38400, B38400},     {57600, B57600},     {115200, B115200},
    {230400, B230400},   {460800, B460800},   {500000, B500000},   {576000, B576000},   {921600, B921600},
    {1000000, B1000000}, {1152000, B1152000}, {1500000, B1500000}, {2000000, B2000000}, {3000000, B3000000},
    {4000000, B4000000},
};

// The termios constant of every rate hal/serial_bauds.hpp lists, in its order.
constexpr bool covers_supported_bauds() {
  if (std::size(kBauds) != kSupportedBauds.size()) return false;
  for (std::size_t i = 0; i < kSupportedBauds.size(); ++i) {
    if (kBauds[i].baud != kSupportedBauds[i]) return false;
  }
  return true;
}
static_assert(covers_supported_bauds());

const BaudConstant* find_baud(int baud) {
  for (const BaudConstant& entry : kBauds) {
    if (entry.baud == baud) return &entry;
  }
  return nullptr;
}

}  // namespace


namespace {

// Closes a device that cannot be used, keeping errno (the reason) for the caller.
int close_refused(int fd) {
  const int error = errno;
  ::close(fd);
  errno = error;
  return -1;
}

// Opens the device non-blocking in raw 8N1 at the speed; -1 with `error` and errno set when it
// cannot.
int open_raw(const std::string& path, const BaudConstant& speed, std::string& error) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    error = std::string("cannot open: ") + std::strerror(errno);
    return -1;
  }
  termios settings{};
  if (::tcgetattr(fd, &settings) != 0) {
    error = std::string("not a serial device: ") + std::strerror(errno);
    return close_refused(fd);
  }
  ::cfmakeraw(&settings);
  settings.c_cflag |= CLOCAL | CREAD;  // ignore modem lines; a bare TX/RX/GND cable is enough
  settings.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB);
  settings.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  settings.c_cc[VMIN] = 0;
  settings.c_cc[VTIME] = 0;
  ::cfsetispeed(&settings, speed.constant);
  ::cfsetospeed(&settings, speed.constant);
  if (::tcsetattr(fd, TCSANOW, &settings) != 0) {
    error = "cannot set raw mode at " + std::to_string(speed.baud) + " baud: " + std::strerror(errno);
    return close_refused(fd);
  }
  return fd;
}

}  // namespace

TermiosSerial::TermiosSerial(const std::string& path, int baud, std::size_t queue_bytes)
    : path_(path), queue_(queue_bytes) {
  const BaudConstant* speed = find_baud(baud);
  if (!speed) throw io::InputError("serial " + path + ": unsupported baud rate " + std::to_string(baud));
  baud_ = baud;
  std::string error;
  fd_ = open_raw(path, *speed, error);
  if (fd_ < 0) throw io::InputError("serial " + path + ": " + error);
}

TermiosSerial::~TermiosSerial() {
  if (fd_ >= 0) ::close(fd_);
}

// The device went away (a USB adapter unplugged, the far end of a pty closed): what was queued
// for it is gone with it, and no message may start torn on the next device.
void TermiosSerial::lose(int error) {
  ::close(fd_);
  fd_ = -1;
  last_error_ = error;
  ++losses_;
  head_ = 0;
  size_ = 0;
  next_attempt_ = Clock::now() + kReopenInterval;
}

bool TermiosSerial::try_reopen() {
  std::string error;
  fd_ = open_raw(path_, *find_baud(baud_), error);
  if (fd_ < 0) {
    last_error_ = errno;  // why it is not there (a reopen after SIGHUP reports it, not "Success")
    next_attempt_ = Clock::now() + kReopenInterval;
    return false;
  }
  return true;
}

void TermiosSerial::reopen_now() {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
    head_ = 0;
    size_ = 0;
  }
  try_reopen();
}

bool TermiosSerial::write_message(std::span<const std::uint8_t> message) {
  if (fd_ < 0 && (Clock::now() < next_attempt_ || !try_reopen())) {
    ++dropped_;
    return false;
  }
  flush();
  if (message.size() > queue_.size() - size_) {
    ++dropped_;
    return false;
  }
  for (const std::uint8_t byte : message) {
    queue_[(head_ + size_) % queue_.size()] = byte;
    ++size_;
  }
  ++sent_;
  flush();
  return true;
}

std::size_t TermiosSerial::read_received(std::span<std::uint8_t> out) {
  if (fd_ < 0 || out.empty()) return 0;
  const ssize_t got = ::read(fd_, out.data(), out.size());
  if (got < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) lose(errno);
  return got > 0 ? static_cast<std::size_t>(got) : 0;
}

void TermiosSerial::flush() {
  while (size_ > 0) {
    // The contiguous run from head_, up to the end of the ring.
    const std::size_t run = std::min(size_, queue_.size() - head_);
    if (fd_ < 0) return;
    const ssize_t written = ::write(fd_, queue_.data() + head_, run);
    if (written < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      lose(errno);
      return;
    }
    if (written <= 0) return;  // the device is full: try again with the next message
    head_ = (head_ + static_cast<std::size_t>(written)) % queue_.size();
    size_ -= static_cast<std::size_t>(written);
  }
}

}  // namespace irloc::hal
