// The --serial argument: none, PATH, PATH:BAUD, paths that contain colons themselves, and
// udp:HOST:PORT, whose port sends each write as one datagram.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/serial_spec.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

TEST(SerialSpec, NoneIsNoPort) { EXPECT_FALSE(parse_serial_spec("none").has_value()); }

TEST(SerialSpec, PathAloneTakesTheDefaultBaud) {
  const auto spec = parse_serial_spec("/dev/ttyAMA0");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->path, "/dev/ttyAMA0");
  EXPECT_EQ(spec->baud, 115200);
}

TEST(SerialSpec, TrailingDigitsAreTheBaud) {
  const auto spec = parse_serial_spec("/dev/ttyUSB0:921600");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->path, "/dev/ttyUSB0");
  EXPECT_EQ(spec->baud, 921600);
}

TEST(SerialSpec, ColonsInsideAPathStayInThePath) {
  const std::string by_path = "/dev/serial/by-path/pci-0000:00:14.0-usb-0:1:1.0-port0";
  const auto spec = parse_serial_spec(by_path);
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->path, by_path);
  const auto with_baud = parse_serial_spec(by_path + ":57600");
  ASSERT_TRUE(with_baud);
  EXPECT_EQ(with_baud->path, by_path);
  EXPECT_EQ(with_baud->baud, 57600);
}

TEST(SerialSpec, BadBaudAndEmptyPathAreErrors) {
  EXPECT_THROW(parse_serial_spec("/dev/ttyUSB0:12345"), io::InputError);
  EXPECT_THROW(parse_serial_spec("/dev/ttyUSB0:99999999999999"), io::InputError);
  EXPECT_THROW(parse_serial_spec(":115200"), io::InputError);
}

TEST(SerialSpec, UdpHostAndPort) {
  const std::optional<SerialSpec> v4 = parse_serial_spec("udp:192.168.1.20:14550");
  ASSERT_TRUE(v4.has_value());
  EXPECT_EQ(v4->udp_host, "192.168.1.20");
  EXPECT_EQ(v4->udp_port, 14550);
  EXPECT_TRUE(v4->path.empty());
  const std::optional<SerialSpec> v6 = parse_serial_spec("udp:[::1]:14551");
  ASSERT_TRUE(v6.has_value());
  EXPECT_EQ(v6->udp_host, "::1");
  EXPECT_EQ(v6->udp_port, 14551);
  for (const char* bad : {"udp:", "udp:host", "udp::14550", "udp:host:", "udp:host:0", "udp:host:65536", "udp:host:14x"}) {
    EXPECT_THROW(parse_serial_spec(bad), io::InputError) << bad;
  }
}

// A UDP socket on the loopback that receives what irlocd would send.
class Receiver {
 public:
  Receiver() {
    fd_ = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address);
    socklen_t size = sizeof address;
    getsockname(fd_, reinterpret_cast<sockaddr*>(&address), &size);
    port_ = ntohs(address.sin_port);
  }
  ~Receiver() { close(fd_); }
  int port() const { return port_; }
  // One datagram, or empty after a second.
  std::vector<std::uint8_t> receive() {
    pollfd waiting{fd_, POLLIN, 0};
    if (poll(&waiting, 1, 1000) != 1) return {};
    std::array<std::uint8_t, 512> buffer{};
    const ssize_t size = recv(fd_, buffer.data(), buffer.size(), 0);
    return {buffer.begin(), buffer.begin() + (size > 0 ? size : 0)};
  }

 private:
  int fd_ = -1;
  int port_ = 0;
};

TEST(SerialSpec, UdpSendsEachMessageAsOneDatagram) {
  Receiver receiver;
  const std::unique_ptr<hal::SerialPort> port = open_serial(parse_serial_spec("udp:127.0.0.1:" + std::to_string(receiver.port())));
  ASSERT_NE(port, nullptr);
  const std::vector<std::uint8_t> first{0xFD, 1, 2, 3}, second{0xFD, 9, 8, 7, 6, 5};
  EXPECT_TRUE(port->write_message(first));
  EXPECT_TRUE(port->write_message(second));
  EXPECT_EQ(receiver.receive(), first);
  EXPECT_EQ(receiver.receive(), second);
  EXPECT_EQ(port->messages_sent(), 2u);
  EXPECT_EQ(port->messages_dropped(), 0u);
}

TEST(SerialSpec, UdpWithNobodyListeningDropsWithoutBlocking) {
  int free_port = 0;
  {
    const Receiver closed;  // a port that was free a moment ago
    free_port = closed.port();
  }
  const std::unique_ptr<hal::SerialPort> port = open_serial(parse_serial_spec("udp:127.0.0.1:" + std::to_string(free_port)));
  const std::vector<std::uint8_t> message{0xFD, 1};
  for (int k = 0; k < 50; ++k) port->write_message(message);
  EXPECT_EQ(port->messages_sent() + port->messages_dropped(), 50u);
  EXPECT_GT(port->messages_dropped(), 0u);  // the loopback's "port unreachable" comes back as a refusal
}

TEST(SerialSpec, UdpHostThatDoesNotResolveIsAnError) {
  EXPECT_THROW(open_serial(parse_serial_spec("udp:no-such-host.invalid:14550")), io::InputError);
}

}  // namespace
}  // namespace irloc::firmware
