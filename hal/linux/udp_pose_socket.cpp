#include "hal/linux/udp_pose_socket.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/input_error.hpp"

namespace irloc::hal {

UdpPoseSocket::UdpPoseSocket(const std::string& host, int port) {
  const std::string name = "--serial udp:" + host + ":" + std::to_string(port) + ": ";
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const int status = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
  if (status != 0) throw io::InputError(name + "cannot resolve the host (" + gai_strerror(status) + ")");
  std::string problem = "no address";
  for (const addrinfo* address = found; address != nullptr && fd_ < 0; address = address->ai_next) {
    const int fd = socket(address->ai_family, address->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, address->ai_protocol);
    if (fd < 0) {
      problem = std::strerror(errno);
      continue;
    }
    // A connected datagram socket: send() needs no address, and a refusal comes back as an error.
    if (connect(fd, address->ai_addr, address->ai_addrlen) != 0) {
      problem = std::strerror(errno);
      close(fd);
      continue;
    }
    fd_ = fd;
  }
  freeaddrinfo(found);
  if (fd_ < 0) throw io::InputError(name + "cannot open a socket (" + problem + ")");
}

UdpPoseSocket::~UdpPoseSocket() {
  if (fd_ >= 0) close(fd_);
}

bool UdpPoseSocket::write_message(std::span<const std::uint8_t> message) {
  const ssize_t written = send(fd_, message.data(), message.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
  if (written != static_cast<ssize_t>(message.size())) {
    ++dropped_;  // EAGAIN (the socket's buffer is full), ECONNREFUSED (nobody listens yet), ...
    return false;
  }
  ++sent_;
  return true;
}

}  // namespace irloc::hal
