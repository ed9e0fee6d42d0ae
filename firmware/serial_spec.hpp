#pragma once
// The serial factory: the --serial argument, "none" or "PATH[:BAUD]" (docs/formats.md), and the
// port it names.

#include <memory>
#include <optional>
#include <string>

#include "hal/serial_port.hpp"

namespace irloc::firmware {

struct SerialSpec {
  std::string path;
  int baud = 115200;  // when the argument names none
};

// Empty for "none". A trailing ":DIGITS" is the baud rate (paths such as /dev/serial/by-path/...
// contain colons, but never end in one followed by digits only). Throws hal::InputError for an
// empty path or a baud rate the device layer does not support.
std::optional<SerialSpec> parse_serial_spec(const std::string& argument);

// The port of a parsed spec (null for none). Throws hal::InputError when the device cannot be opened.
std::unique_ptr<hal::SerialPort> open_serial(const std::optional<SerialSpec>& spec);

}  // namespace irloc::firmware
