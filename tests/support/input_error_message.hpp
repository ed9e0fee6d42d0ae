#pragma once
// The one-line message of the io::InputError that a call throws, for tests of error paths.

#include <string>

#include <gtest/gtest.h>

#include "io/input_error.hpp"

namespace irloc::test {

// what() of the InputError `call` throws; a test failure (and "") when it throws none.
template <typename Call>
std::string input_error_message(Call&& call) {
  try {
    call();
  } catch (const io::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

}  // namespace irloc::test
