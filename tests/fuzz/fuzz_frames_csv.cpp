// libFuzzer target: a dataset's frames.csv, beside two valid 8 x 6 frames, read by the `dir:`
// camera to its end.
#include "algo/core/image.hpp"
#include "io/dataset/pgm.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool frames = [] {
    irloc::Image8 image(8, 6);
    irloc::fuzz::write_file("frame_000000.pgm", irloc::io::encode_pgm(image.view()));
    irloc::fuzz::write_file("frame_000001.pgm", irloc::io::encode_pgm(image.view()));
    return true;
  }();
  (void)frames;
  irloc::fuzz::write_file("frames.csv", data, size);
  irloc::fuzz::replay_dataset(8, 6);
  return 0;
}
