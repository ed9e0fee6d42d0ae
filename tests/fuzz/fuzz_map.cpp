// libFuzzer target: the marker map reader.
#include "io/config/map_file.hpp"
#include "io/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::io::load_marker_map(irloc::fuzz::write_file("map.yaml", data, size));
  } catch (const irloc::io::InputError&) {
  }
  return 0;
}
