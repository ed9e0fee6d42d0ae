#pragma once
// The --serial argument: "none" or "PATH[:BAUD]" (docs/formats.md).

#include <optional>
#include <string>

namespace irloc::firmware {

struct SerialSpec {
  std::string path;
  int baud = 115200;  // when the argument names none
};

// Empty for "none". A trailing ":DIGITS" is the baud rate (paths such as /dev/serial/by-path/...
// contain colons, but never end in one followed by digits only). Throws hal::InputError for an
// empty path or a baud rate the device layer does not support.
std::optional<SerialSpec> parse_serial_spec(const std::string& argument);

}  // namespace irloc::firmware
