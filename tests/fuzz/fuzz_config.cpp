// libFuzzer target: the config reader, beside a valid calibration and map it may name (and the
// readers of those it reaches through them).
#include "io/config/config_file.hpp"
#include "io/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"

namespace {

void write_companions() {
  static const bool written = [] {
    irloc::fuzz::write_file("calib.yaml", R"(image_width: 160
image_height: 120
camera_matrix: {rows: 3, cols: 3, data: [120, 0, 79.5, 0, 120, 59.5, 0, 0, 1]}
distortion_model: plumb_bob
distortion_coefficients: {rows: 1, cols: 5, data: [-0.1, 0.02, 0, 0, 0]}
)");
    irloc::fuzz::write_file("map.yaml", R"(dot_markers:
  - {id: 1782, origin: [1, 2, 2.6], yaw: 0.3}
square_markers:
  - name: hall
    corners: [[-1, -1, 2.3], [1, -1, 2.3], [1, 1, 2.3], [-1, 1, 2.3]]
led_landmarks:
  - {name: L1, position: [3, 0, 2.5]}
)");
    return true;
  }();
  (void)written;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  write_companions();
  try {
    irloc::io::load_robot_config(irloc::fuzz::write_file("config.yaml", data, size));
  } catch (const irloc::io::InputError&) {
  }
  return 0;
}
