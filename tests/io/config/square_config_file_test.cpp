// The optional `square` section of the config YAML.

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/config_file.hpp"
#include "io/input_error.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;

class SquareConfigFile : public ::testing::Test {
 protected:
  void SetUp() override {
    write("calib.yaml", R"(image_width: 640
image_height: 512
camera_matrix: {rows: 3, cols: 3, data: [181, 0, 319.5, 0, 181, 255.5, 0, 0, 1]}
distortion_model: equisolid
distortion_coefficients: {rows: 1, cols: 0, data: []}
)");
    write("map.yaml", R"(square_markers:
  - name: hall
    corners: [[-1, -1, 2.3], [1, -1, 2.3], [1, 1, 2.3], [-1, 1, 2.3]]
)");
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  void write_config(const std::string& square_section) {
    write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0.05, 0, 0.3]}\n"
                         "robot:\n  dof: 3\nmap: map.yaml\n" + square_section);
  }
  std::string error() {
    return test::input_error_message([&] { load_robot_config(dir_ / "config.yaml"); });
  }
  test::TempDir dir_;
};

TEST_F(SquareConfigFile, AbsentSectionGivesTheDefaults) {
  write_config("");
  const RobotConfig config = load_robot_config(dir_ / "config.yaml");
  EXPECT_EQ(config.setup.square.threshold, square::SquareConfig{}.threshold);
  EXPECT_EQ(config.setup.square.side_tolerance, square::SquareConfig{}.side_tolerance);
}

TEST_F(SquareConfigFile, ReadsEveryKey) {
  write_config(R"(square:
  threshold: 40
  max_ray_angle: 1.2
  side_tolerance: 0.05
  angle_tolerance: 0.1
  tilted_side_tolerance: 0.25
  tilted_angle_tolerance: 0.3
  min_visible_fraction: 0.4
  solid_min_fill: 0.9
  solid_max_gap_rate: 0.2
  dashed_min_gap_rate: 0.6
  max_corner_residual: 0.01
  max_side_error: 0.02
  clear_win_ratio: 1.5
  min_dash_coherence: 0.4
  max_prior_age: 1.0
  max_prior_distance: 0.5
)");
  const square::SquareConfig square = load_robot_config(dir_ / "config.yaml").setup.square;
  EXPECT_EQ(square.threshold, 40);
  EXPECT_EQ(square.max_ray_angle, 1.2);
  EXPECT_EQ(square.side_tolerance, 0.05);
  EXPECT_EQ(square.angle_tolerance, 0.1);
  EXPECT_EQ(square.tilted_side_tolerance, 0.25);
  EXPECT_EQ(square.tilted_angle_tolerance, 0.3);
  EXPECT_EQ(square.min_visible_fraction, 0.4);
  EXPECT_EQ(square.solid_min_fill, 0.9);
  EXPECT_EQ(square.solid_max_gap_rate, 0.2);
  EXPECT_EQ(square.dashed_min_gap_rate, 0.6);
  EXPECT_EQ(square.max_corner_residual, 0.01);
  EXPECT_EQ(square.max_side_error, 0.02);
  EXPECT_EQ(square.clear_win_ratio, 1.5);
  EXPECT_EQ(square.min_dash_coherence, 0.4);
  EXPECT_EQ(square.max_prior_age, 1.0);
  EXPECT_EQ(square.max_prior_distance, 0.5);
}

TEST_F(SquareConfigFile, UnknownKeyIsNamed) {
  write_config("square:\n  side_tolerence: 0.1\n");
  const std::string message = error();
  EXPECT_THAT(message, HasSubstr("config.yaml:8"));
  EXPECT_THAT(message, HasSubstr("square.side_tolerence"));
}

TEST_F(SquareConfigFile, OutOfRangeValuesAreNamed) {
  write_config("square:\n  angle_tolerance: 10\n");
  EXPECT_THAT(error(), HasSubstr("square.angle_tolerance: must be in"));
  write_config("square:\n  threshold: -3\n");
  EXPECT_THAT(error(), HasSubstr("square.threshold"));
  write_config("square:\n  solid_max_gap_rate: 0.6\n  dashed_min_gap_rate: 0.5\n");
  EXPECT_THAT(error(), HasSubstr("square.dashed_min_gap_rate: must be above solid_max_gap_rate"));
}

}  // namespace
}  // namespace irloc::io
