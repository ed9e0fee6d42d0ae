#pragma once
// A device that worked and stopped: a camera that no longer delivers frames, unplugged or hung.
// Unlike io::InputError (bad input, fatal), it may come back: irlocd keeps running and reopens it.

#include <stdexcept>
#include <string>

namespace irloc::hal {

// what() is one line for the user: "DEVICE: PROBLEM".
class DeviceLost : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace irloc::hal
