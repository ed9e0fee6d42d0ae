// The optional `mount_watch` section of the config YAML: on by default for a level robot, off for
// dof 6, where asking for it is an error naming the field.

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

class MountWatchConfigFile : public ::testing::Test {
 protected:
  void SetUp() override {
    write("calib.yaml", R"(image_width: 640
image_height: 480
camera_matrix: {rows: 3, cols: 3, data: [400, 0, 319.5, 0, 400, 239.5, 0, 0, 1]}
distortion_model: plumb_bob
distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}
)");
    write("map.yaml", "dot_markers:\n  - {id: 1782, origin: [1, 2, 2.6], yaw: 0}\n");
  }
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  void write_config(int dof, const std::string& section) {
    write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0.05, 0, 0.3]}\n"
                         "robot:\n  dof: " + std::to_string(dof) + "\nmap: map.yaml\n" + section);
  }
  RobotConfig load() { return load_robot_config(dir_ / "config.yaml"); }
  std::string error() {
    return test::input_error_message([&] { load(); });
  }
  test::TempDir dir_;
};

TEST_F(MountWatchConfigFile, OnForALevelRobotOffForDofSix) {
  write_config(3, "");
  EXPECT_TRUE(load().mount_watch.enabled);
  EXPECT_EQ(load().mount_watch.tolerance, calibration::MountWatchConfig{}.tolerance);
  write_config(4, "");
  EXPECT_TRUE(load().mount_watch.enabled);
  write_config(6, "");
  EXPECT_FALSE(load().mount_watch.enabled);
  write_config(6, "mount_watch:\n  enabled: false\n");
  EXPECT_FALSE(load().mount_watch.enabled);
}

TEST_F(MountWatchConfigFile, ReadsEveryKey) {
  write_config(3, "mount_watch:\n  enabled: false\n  tolerance: 0.005\n  time_constant: 120\n  sigmas: 3\n"
                  "  floor_sigma: 0.01\n");
  const calibration::MountWatchConfig watch = load().mount_watch;
  EXPECT_FALSE(watch.enabled);
  EXPECT_EQ(watch.tolerance, 0.005);
  EXPECT_EQ(watch.time_constant, 120);
  EXPECT_EQ(watch.sigmas, 3);
  EXPECT_EQ(watch.floor_sigma, 0.01);
}

TEST_F(MountWatchConfigFile, BadValuesAreNamed) {
  write_config(6, "mount_watch:\n  enabled: true\n");
  EXPECT_THAT(error(), HasSubstr("mount_watch.enabled: the mount's tilt cannot be watched with robot.dof 6"));
  write_config(3, "mount_watch:\n  tolerance: 1e308\n");
  EXPECT_THAT(error(), HasSubstr("mount_watch.tolerance: must be in"));
  write_config(3, "mount_watch:\n  time_constnt: 60\n");
  EXPECT_THAT(error(), HasSubstr("mount_watch.time_constnt"));
  write_config(3, "mount_watch:\n  sigmas: 4\n  sigmas: 2\n");
  EXPECT_THAT(error(), HasSubstr("sigmas"));
}

}  // namespace
}  // namespace irloc::io
