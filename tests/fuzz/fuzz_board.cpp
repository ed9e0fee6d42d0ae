// libFuzzer target: the board file reader.
#include "io/config/board_file.hpp"
#include "io/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::io::load_board(irloc::fuzz::write_file("board.yaml", data, size));
  } catch (const irloc::io::InputError&) {
  }
  return 0;
}
