#include "firmware/warning_log.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdarg>

namespace irloc::firmware {
namespace {

std::atomic<WarningListener*> listener{nullptr};

}  // namespace

void set_warning_listener(WarningListener* new_listener) { listener.store(new_listener); }

void print_warning(std::FILE* out, const char* format, ...) {
  std::array<char, 256> text{};
  va_list arguments;
  va_start(arguments, format);
  const int size = std::vsnprintf(text.data(), text.size(), format, arguments);
  va_end(arguments);
  const std::string_view line(text.data(), static_cast<std::size_t>(std::clamp(size, 0, static_cast<int>(text.size()) - 1)));
  std::fprintf(out, "irlocd: %.*s\n", static_cast<int>(line.size()), line.data());
  if (WarningListener* current = listener.load()) current->warning(line);
}

}  // namespace irloc::firmware
