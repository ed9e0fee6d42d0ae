// libFuzzer target: the camera_info calibration reader.
#include "io/config/calibration_file.hpp"
#include "io/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::io::load_camera_info(irloc::fuzz::write_file("calib.yaml", data, size));
  } catch (const irloc::io::InputError&) {
  }
  return 0;
}
