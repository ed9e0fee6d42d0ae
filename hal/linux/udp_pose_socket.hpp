#pragma once
// The pose stream over UDP, as a companion computer sends MAVLink to an autopilot or a ground
// station: each write (the messages of one pose attempt, whole) as one datagram to HOST:PORT, sent
// without blocking. A datagram the socket does not take now, or one the peer refused (nobody
// listening), is dropped whole and counted.

#include <cstdint>
#include <string>

#include "hal/serial_port.hpp"

namespace irloc::hal {

class UdpPoseSocket final : public SerialPort {
 public:
  // HOST: a name or an IPv4/IPv6 address; PORT 1-65535. Throws io::InputError "--serial udp:HOST:PORT:
  // problem" when the address does not resolve or no socket can be made.
  UdpPoseSocket(const std::string& host, int port);
  ~UdpPoseSocket() override;
  UdpPoseSocket(const UdpPoseSocket&) = delete;
  UdpPoseSocket& operator=(const UdpPoseSocket&) = delete;

  bool write_message(std::span<const std::uint8_t> message) override;
  std::uint64_t messages_sent() const override { return sent_; }
  std::uint64_t messages_dropped() const override { return dropped_; }

 private:
  int fd_ = -1;
  std::uint64_t sent_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace irloc::hal
