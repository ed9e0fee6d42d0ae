#pragma once
// The warnings irlocd prints while running (camera lost, strobe out of sync, mount tilt, ...): one
// line "irlocd: TEXT" on the given stream, and the same text to the pose-stream link where its
// protocol carries text (MAVLink STATUSTEXT), so that a ground station sees what stderr says.
// Allocates nothing.

#include <cstdio>
#include <string_view>

namespace irloc::firmware {

class WarningListener {
 public:
  virtual ~WarningListener() = default;
  virtual void warning(std::string_view text) = 0;
};

// The one listener of the process (the link), or null. It must outlive its registration.
void set_warning_listener(WarningListener* listener);

// Registers a listener for its scope.
class ScopedWarningListener {
 public:
  explicit ScopedWarningListener(WarningListener* listener) { set_warning_listener(listener); }
  ~ScopedWarningListener() { set_warning_listener(nullptr); }
  ScopedWarningListener(const ScopedWarningListener&) = delete;
  ScopedWarningListener& operator=(const ScopedWarningListener&) = delete;
};

// Texts longer than 255 characters are cut.
void print_warning(std::FILE* out, const char* format, ...) __attribute__((format(printf, 2, 3)));

}  // namespace irloc::firmware
