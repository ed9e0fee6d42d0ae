// The optional `led:` section of the config YAML.

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/config_file.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;

class LedConfigFile : public ::testing::Test {
 protected:
  void SetUp() override {
    write("calib.yaml", R"(image_width: 640
image_height: 480
camera_matrix: {rows: 3, cols: 3, data: [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1]}
distortion_model: plumb_bob
distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}
)");
    write("map.yaml", "led_landmarks:\n  - {name: L1, position: [4, 0, 1.2]}\n  - {name: L2, position: [4, 1, 0.8]}\n");
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  void write_config(const std::string& led_section) {
    write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0.3]}\n"
                         "robot:\n  dof: 6\nmap: map.yaml\n" + led_section);
  }
  std::string error() {
    return test::input_error_message([&] { load_robot_config(dir_ / "config.yaml"); });
  }
  test::TempDir dir_;
};

TEST_F(LedConfigFile, AbsentSectionGivesTheDefaults) {
  write_config("");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.led.threshold, led::LedSourceConfig{}.threshold);
  EXPECT_EQ(config.setup.map.led_landmarks.size(), 2u);
}

TEST_F(LedConfigFile, ReadsKeys) {
  write_config("led:\n  max_area: 50\n  threshold: 0.3\n  max_missing: 0\n  max_tilt: 0.1\n  pixel_sigma: 0.15\n"
               "  cone_tolerance: 0.1\n  reach_window: 0.8\n  max_yaw_sigma: 0.02\n");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.led.max_area, 50);
  EXPECT_DOUBLE_EQ(config.setup.led.threshold, 0.3);
  EXPECT_EQ(config.setup.led.max_missing, 0);
  EXPECT_DOUBLE_EQ(config.setup.led.max_tilt, 0.1);
  EXPECT_DOUBLE_EQ(config.setup.led.cone_tolerance, 0.1);
  EXPECT_DOUBLE_EQ(config.setup.led.reach_window, 0.8);
  EXPECT_DOUBLE_EQ(config.setup.led.pixel_sigma, 0.15);
  EXPECT_DOUBLE_EQ(config.setup.led.max_yaw_sigma, 0.02);
}

TEST_F(LedConfigFile, UnknownKeyAndBadValuesNameTheField) {
  write_config("led:\n  treshold: 0.3\n");
  EXPECT_THAT(error(), HasSubstr("treshold"));
  write_config("led:\n  threshold: 2\n");
  EXPECT_THAT(error(), AllOf(HasSubstr("config.yaml"), HasSubstr("threshold"), HasSubstr("must be in")));
  write_config("led:\n  min_height: 0.5\n  max_height: 0.1\n");
  EXPECT_THAT(error(), HasSubstr("max_height"));
}

}  // namespace
}  // namespace irloc::io
