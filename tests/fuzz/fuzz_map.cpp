// libFuzzer target: the marker map reader.
#include "hal/config/map_file.hpp"
#include "hal/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::hal::load_marker_map(irloc::fuzz::write_file("map.yaml", data, size));
  } catch (const irloc::hal::InputError&) {
  }
  return 0;
}
