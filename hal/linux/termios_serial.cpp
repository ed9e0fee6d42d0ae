#include "hal/linux/termios_serial.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "hal/input_error.hpp"

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

const BaudConstant* find_baud(int baud) {
  for (const BaudConstant& entry : kBauds) {
    if (entry.baud == baud) return &entry;
  }
  return nullptr;
}

}  // namespace

bool TermiosSerial::is_supported_baud(int baud) { return find_baud(baud) != nullptr; }

TermiosSerial::TermiosSerial(const std::string& path, int baud, std::size_t queue_bytes)
    : path_(path), queue_(queue_bytes) {
  const BaudConstant* speed = find_baud(baud);
  if (!speed) throw InputError("serial " + path + ": unsupported baud rate " + std::to_string(baud));
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) throw InputError("serial " + path + ": cannot open: " + std::strerror(errno));

  termios settings{};
  if (::tcgetattr(fd_, &settings) != 0) {
    const int error = errno;
    ::close(fd_);
    throw InputError("serial " + path + ": not a serial device: " + std::strerror(error));
  }
  ::cfmakeraw(&settings);
  settings.c_cflag |= CLOCAL | CREAD;  // ignore modem lines; a bare TX/RX/GND cable is enough
  settings.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB);
  settings.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  settings.c_cc[VMIN] = 0;
  settings.c_cc[VTIME] = 0;
  ::cfsetispeed(&settings, speed->constant);
  ::cfsetospeed(&settings, speed->constant);
  if (::tcsetattr(fd_, TCSANOW, &settings) != 0) {
    const int error = errno;
    ::close(fd_);
    throw InputError("serial " + path + ": cannot set raw mode at " + std::to_string(baud) + " baud: " + std::strerror(error));
  }
}

TermiosSerial::~TermiosSerial() {
  if (fd_ >= 0) ::close(fd_);
}

bool TermiosSerial::write_message(std::span<const std::uint8_t> message) {
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

void TermiosSerial::flush() {
  while (size_ > 0) {
    // The contiguous run from head_, up to the end of the ring.
    const std::size_t run = std::min(size_, queue_.size() - head_);
    const ssize_t written = ::write(fd_, queue_.data() + head_, run);
    if (written <= 0) return;  // EAGAIN (the device is full) or an error: try again next message
    head_ = (head_ + static_cast<std::size_t>(written)) % queue_.size();
    size_ -= static_cast<std::size_t>(written);
  }
}

}  // namespace irloc::hal
