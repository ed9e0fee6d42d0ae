// libFuzzer target: the simulator's scenario reader.
#include "io/input_error.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::sim::load_scenario(irloc::fuzz::write_file("scenario.yaml", data, size));
  } catch (const irloc::io::InputError&) {
  }
  return 0;
}
