#include "firmware/serial_spec.hpp"

#include <algorithm>
#include <cctype>

#include "io/input_error.hpp"
#include "hal/serial_bauds.hpp"
#include "hal/linux/termios_serial.hpp"
#include "hal/linux/udp_pose_socket.hpp"

namespace irloc::firmware {

namespace {

SerialSpec parse_udp(const std::string& argument) {
  const std::string address = argument.substr(4);  // after "udp:"
  const std::string problem = "--serial " + argument + ": expected udp:HOST:PORT, PORT 1-65535";
  const std::size_t colon = address.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == address.size()) throw io::InputError(problem);
  std::string host = address.substr(0, colon);
  const std::string port = address.substr(colon + 1);
  if (port.size() > 5 || !std::all_of(port.begin(), port.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
    throw io::InputError(problem);
  }
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  SerialSpec spec;
  spec.udp_host = host;
  spec.udp_port = std::stoi(port);
  if (spec.udp_port < 1 || spec.udp_port > 65535) throw io::InputError(problem);
  return spec;
}

}  // namespace

std::optional<SerialSpec> parse_serial_spec(const std::string& argument) {
  if (argument == "none") return std::nullopt;
  if (argument.rfind("udp:", 0) == 0) return parse_udp(argument);
  SerialSpec spec;
  spec.path = argument;
  const std::size_t colon = argument.rfind(':');
  if (colon != std::string::npos && colon + 1 < argument.size()) {
    const std::string tail = argument.substr(colon + 1);
    if (std::all_of(tail.begin(), tail.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
      spec.path = argument.substr(0, colon);
      if (tail.size() > 8 || !hal::is_supported_baud(std::stoi(tail))) {
        throw io::InputError("--serial " + argument + ": " + hal::unsupported_baud_message(tail));
      }
      spec.baud = std::stoi(tail);
    }
  }
  if (spec.path.empty()) throw io::InputError("--serial " + argument + ": no device path (expected none or PATH[:BAUD])");
  return spec;
}

std::unique_ptr<hal::SerialPort> open_serial(const std::optional<SerialSpec>& spec) {
  if (!spec) return nullptr;
  if (spec->udp_port != 0) return std::make_unique<hal::UdpPoseSocket>(spec->udp_host, spec->udp_port);
  return std::make_unique<hal::TermiosSerial>(spec->path, spec->baud);
}

}  // namespace irloc::firmware
