#include "firmware/service_notifier.hpp"

#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

sockaddr_un notify_address(const std::string& name, socklen_t& length) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (name.size() < 2 || (name[0] != '/' && name[0] != '@') || name.size() >= sizeof(address.sun_path)) {
    throw io::InputError("NOTIFY_SOCKET=" + name + ": expected an absolute socket path or @abstract name");
  }
  std::memcpy(address.sun_path, name.data(), name.size());
  if (name[0] == '@') address.sun_path[0] = '\0';  // Linux abstract namespace
  length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name.size() + (name[0] == '/' ? 1 : 0));
  return address;
}

// $WATCHDOG_USEC, unless $WATCHDOG_PID names another process (the variables were inherited).
std::chrono::microseconds watchdog_usec() {
  const char* usec = std::getenv("WATCHDOG_USEC");
  if (!usec) return std::chrono::microseconds(0);
  if (const char* pid = std::getenv("WATCHDOG_PID"); pid && std::to_string(::getpid()) != pid) {
    return std::chrono::microseconds(0);
  }
  char* end = nullptr;
  const unsigned long long value = std::strtoull(usec, &end, 10);
  if (*usec == '\0' || *end != '\0' || value == 0 || value > 3600ULL * 1000 * 1000 * 24) {
    throw io::InputError(std::string("WATCHDOG_USEC=") + usec + ": expected microseconds, 1 to a day");
  }
  return std::chrono::microseconds(value);
}

}  // namespace

ServiceNotifier::ServiceNotifier() {
  const char* name = std::getenv("NOTIFY_SOCKET");
  if (!name) return;
  socklen_t length = 0;
  const sockaddr_un address = notify_address(name, length);
  watchdog_interval_ = watchdog_usec();
  socket_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (socket_ < 0) throw io::InputError(std::string("NOTIFY_SOCKET=") + name + ": cannot create a socket: " + std::strerror(errno));
  if (::connect(socket_, reinterpret_cast<const sockaddr*>(&address), length) != 0) {
    const int error = errno;
    ::close(socket_);
    socket_ = -1;
    throw io::InputError(std::string("NOTIFY_SOCKET=") + name + ": cannot connect: " + std::strerror(error));
  }
}

ServiceNotifier::~ServiceNotifier() {
  if (socket_ >= 0) ::close(socket_);
}

void ServiceNotifier::send(const char* message) {
  // A full queue or a service manager gone away must not stop the robot: the message is dropped.
  if (socket_ >= 0) (void)::send(socket_, message, std::strlen(message), MSG_NOSIGNAL | MSG_DONTWAIT);
}

void ServiceNotifier::pet(Clock::time_point now) {
  if (socket_ < 0 || watchdog_interval_.count() == 0) return;
  if (petted_ && now - last_pet_ < watchdog_interval_ / 2) return;
  send("WATCHDOG=1");
  last_pet_ = now;
  petted_ = true;
}

}  // namespace irloc::firmware
