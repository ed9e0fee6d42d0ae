// libFuzzer target: the board file reader.
#include "hal/config/board_file.hpp"
#include "hal/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::hal::load_board(irloc::fuzz::write_file("board.yaml", data, size));
  } catch (const irloc::hal::InputError&) {
  }
  return 0;
}
