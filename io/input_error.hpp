#pragma once
// The one error type for bad input: a missing file, malformed YAML, a wrong value, a bad frame.

#include <stdexcept>
#include <string>

namespace irloc::io {

// what() is one complete line for the user: "FILE[:LINE]: [FIELD: ]PROBLEM".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace irloc::io
