#pragma once
// The serial factory: the --serial argument, "none", "PATH[:BAUD]" or "udp:HOST:PORT"
// (docs/formats.md), and the port it names.

#include <memory>
#include <optional>
#include <string>

#include "hal/serial_port.hpp"

namespace irloc::firmware {

struct SerialSpec {
  std::string path;   // a device; empty for UDP
  int baud = 115200;  // when the argument names none
  std::string udp_host;  // udp:HOST:PORT (HOST may be [IPv6])
  int udp_port = 0;
};

// Empty for "none". A trailing ":DIGITS" is the baud rate (paths such as /dev/serial/by-path/...
// contain colons, but never end in one followed by digits only). "udp:HOST:PORT" sends each
// write (the messages of one pose attempt) as one UDP datagram. Throws io::InputError for an empty path, a baud rate the device
// layer does not support, or a UDP address without a host or with a port outside 1-65535.
std::optional<SerialSpec> parse_serial_spec(const std::string& argument);

// The port of a parsed spec (null for none). Throws io::InputError when the device cannot be opened.
std::unique_ptr<hal::SerialPort> open_serial(const std::optional<SerialSpec>& spec);

}  // namespace irloc::firmware
