// libFuzzer target: a PGM frame, as its header parser and the `dir:` camera read it (a dataset
// whose frames.csv lists that one file, calibrated 8 x 6).
#include <span>

#include "io/input_error.hpp"
#include "io/dataset/pgm.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool index = [] {
    irloc::fuzz::write_file("frames.csv", "seq,t_ns,led,file\n0,1000,1,frame_000000.pgm\n");
    return true;
  }();
  (void)index;
  try {
    irloc::io::parse_pgm_header(std::as_bytes(std::span(data, size)), "fuzz.pgm");
  } catch (const irloc::io::InputError&) {
  }
  irloc::fuzz::write_file("frame_000000.pgm", data, size);
  irloc::fuzz::replay_dataset(8, 6);
  return 0;
}
