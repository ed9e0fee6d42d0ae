#pragma once
// The serial baud rates irloc can set (termios' standard and Linux's high rates): one list for
// every place a rate is given (--serial PATH:BAUD, a board file's serial.baud) and the device
// that sets it (hal/linux/termios_serial).

#include <algorithm>
#include <array>
#include <string>

namespace irloc::hal {

inline constexpr std::array<int, 16> kSupportedBauds = {9600,    19200,   38400,   57600,   115200,  230400,
                                                        460800,  500000,  576000,  921600,  1000000, 1152000,
                                                        1500000, 2000000, 3000000, 4000000};

inline bool is_supported_baud(int baud) {
  return std::find(kSupportedBauds.begin(), kSupportedBauds.end(), baud) != kSupportedBauds.end();
}

// "unsupported baud rate 12345 (supported: 9600, ..., 4000000)"
inline std::string unsupported_baud_message(const std::string& baud) {
  std::string text = "unsupported baud rate ";
  text.append(baud).append(" (supported:");
  for (const int supported : kSupportedBauds) text.append(" ").append(std::to_string(supported));
  return text.append(")");
}

}  // namespace irloc::hal
