// libFuzzer target: the camera_info calibration reader.
#include "hal/config/calibration_file.hpp"
#include "hal/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    irloc::hal::load_camera_info(irloc::fuzz::write_file("calib.yaml", data, size));
  } catch (const irloc::hal::InputError&) {
  }
  return 0;
}
