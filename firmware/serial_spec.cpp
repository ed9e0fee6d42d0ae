#include "firmware/serial_spec.hpp"

#include <algorithm>
#include <cctype>

#include "hal/input_error.hpp"
#include "hal/linux/termios_serial.hpp"

namespace irloc::firmware {

std::optional<SerialSpec> parse_serial_spec(const std::string& argument) {
  if (argument == "none") return std::nullopt;
  SerialSpec spec;
  spec.path = argument;
  const std::size_t colon = argument.rfind(':');
  if (colon != std::string::npos && colon + 1 < argument.size()) {
    const std::string tail = argument.substr(colon + 1);
    if (std::all_of(tail.begin(), tail.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
      spec.path = argument.substr(0, colon);
      if (tail.size() > 8) throw hal::InputError("--serial " + argument + ": unsupported baud rate " + tail);
      spec.baud = std::stoi(tail);
      if (!hal::TermiosSerial::is_supported_baud(spec.baud)) {
        throw hal::InputError("--serial " + argument + ": unsupported baud rate " + tail);
      }
    }
  }
  if (spec.path.empty()) throw hal::InputError("--serial " + argument + ": no device path (expected none or PATH[:BAUD])");
  return spec;
}

std::unique_ptr<hal::SerialPort> open_serial(const std::optional<SerialSpec>& spec) {
  if (!spec) return nullptr;
  return std::make_unique<hal::TermiosSerial>(spec->path, spec->baud);
}

}  // namespace irloc::firmware
