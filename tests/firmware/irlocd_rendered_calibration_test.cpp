// irlocd --calibrate on rendered drives that cannot improve a calibration (docs/calibration.md,
// "Degenerate drives"): a robot standing still is refused for its views whatever its input; a
// short straight drive refuses to change a correct calibration (no evidence against it) and
// still replaces a wrong one. Nothing is written when refused.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/firmware/rendered_robot_scenario.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

using ::testing::HasSubstr;

// 400 px focal length, f / 2.3 m: a 1 px principal point error moves a pose by 6 mm.
test::ScenarioText drive(const std::string& trajectory, int frames) {
  test::ScenarioText text = test::rendered_robot_scenario(400, "[-0.1, 0.02, 0, 0, 0]", 30);
  text.seed = 32;
  text.frames = frames;
  text.trajectory = trajectory;
  text.map = "  dot_markers:\n";
  int id = 101;
  for (int x = -2; x <= 2; ++x) {
    for (int y = -1; y <= 1; ++y, id += 37) {
      text.map += "    - {id: " + std::to_string(id) + ", origin: [" + std::to_string(x) + ".0, " + std::to_string(y) +
                  ".0, 2.6], yaw: " + std::to_string(0.4 * (id % 15)) + "}\n";
    }
  }
  return text;
}

class IrlocdRenderedCalibration : public ::testing::Test {
 protected:
  std::filesystem::path dataset() const { return dir_ / "dataset"; }

  void render(const test::ScenarioText& text) {
    for (const sim::TruthRow& row : sim::render_dataset(sim::parse_scenario(text.yaml(), "scenario.yaml"), dataset())) {
      truth_[row.seq] = row;
    }
    // A wrong calibration in what a drive without turns shows: focal lengths 1 % long, k1 10 %
    // strong.
    std::ofstream(dataset() / "wrong_calib.yaml")
        << "image_width: 640\nimage_height: 480\ncamera_name: wrong\n"
           "camera_matrix: {rows: 3, cols: 3, data: [404, 0, 319.5, 0, 404, 239.5, 0, 0, 1]}\n"
           "distortion_model: plumb_bob\ndistortion_coefficients: {rows: 1, cols: 5, data: [-0.11, 0.02, 0, 0, 0]}\n";
    std::ofstream(dataset() / "wrong_config.yaml")
        << "camera:\n  calibration: wrong_calib.yaml\n  mount: {preset: up, xyz: [0.05, 0, 0.3]}\n"
           "robot:\n  dof: 3\nmap: map.yaml\n";
  }

  test::ProcessResult calibrate(const std::string& config) const { return replay(config, {"--calibrate", out().string()}); }
  test::ProcessResult replay(const std::string& config, std::vector<std::string> more = {}) const {
    std::vector<std::string> arguments = {IRLOCD_PATH, "--config", (dataset() / config).string(), "--camera",
                                          "dir:" + dataset().string(), "--serial", "none", "--pose-csv", pose_csv().string()};
    arguments.insert(arguments.end(), more.begin(), more.end());
    return test::run_to_end(arguments, dir_ / "stderr.txt");
  }
  std::filesystem::path pose_csv() const { return dir_ / "pose.csv"; }
  std::filesystem::path out() const { return dir_ / "calibrated"; }
  struct Errors {
    int ok = 0;
    double position_rms_m = 0;
  };
  // The last replay's ok poses and their position RMS against the truth.
  Errors errors() const {
    Errors result;
    double sum = 0;
    for (const PoseEstimate& pose : sim::read_pose_csv(pose_csv())) {
      if (!pose.ok) continue;
      const sim::TruthRow& row = truth_.at(pose.seq);
      sum += (pose.x - row.x) * (pose.x - row.x) + (pose.y - row.y) * (pose.y - row.y);
      ++result.ok;
    }
    result.position_rms_m = std::sqrt(sum / std::max(result.ok, 1));
    return result;
  }

  test::TempDir dir_;
  std::map<std::uint64_t, sim::TruthRow> truth_;
};

// 12 pose attempts from one spot: one view, whatever the calibration says.
TEST_F(IrlocdRenderedCalibration, AStandingRobotIsRefusedForItsViews) {
  render(drive("  type: static\n  pose: [0.1, -0.2, 0.3]\n", 24));
  for (const char* config : {"config.yaml", "wrong_config.yaml"}) {
    const test::ProcessResult run = calibrate(config);
    EXPECT_EQ(run.status, 1) << config;
    EXPECT_THAT(run.stderr_text, HasSubstr("--calibrate: no calibration from this drive: the drive shows the ceiling from 1 "
                                           "distinct views (0.00 m driven, 0 deg turned"))
        << run.stderr_text;
    EXPECT_FALSE(std::filesystem::exists(out() / "config.yaml"));
  }
}

// 1.3 m straight at 1.2 m/s (20 pose attempts, about 13 views, no turn): the correct
// calibration stands; the wrong one (whose poses all fall below the confidence floor) is replaced,
// the mount's x (it needs turning) and the principal point (the drive does not show it) kept.
TEST_F(IrlocdRenderedCalibration, AShortStraightDriveKeepsACorrectCalibrationAndCorrectsAWrongOne) {
  render(drive("  type: waypoints\n  points: [[-0.7, 0.1], [0.9, 0.1]]\n  speed: 1.2\n", 40));
  const test::ProcessResult correct = calibrate("config.yaml");
  EXPECT_EQ(correct.status, 1);
  EXPECT_THAT(correct.stderr_text, HasSubstr("--calibrate: no calibration from this drive: it shows no evidence against "
                                             "the input calibration"))
      << correct.stderr_text;
  EXPECT_FALSE(std::filesystem::exists(out() / "config.yaml"));

  // A wrong one: the drive has evidence against it, and it is replaced.
  const test::ProcessResult wrong = calibrate("wrong_config.yaml");
  ASSERT_EQ(wrong.status, 0) << wrong.stderr_text;
  const std::string report = test::read_text(out() / "calibration_report.txt");
  EXPECT_THAT(report, HasSubstr("mount x      not observable on this drive: it turned 0 deg")) << report;
  EXPECT_THAT(report, HasSubstr("evidence against the input: chi-square")) << report;
  // The drive cannot tell the principal point from a shift of every pose: it keeps the input's
  // (true) one. Moved by its prior's pull, it left every pose about 19 mm off.
  EXPECT_THAT(report, HasSubstr("cx           not observable on this drive alone")) << report;
  ASSERT_EQ(replay((out() / "config.yaml").string()).status, 0);
  const Errors refined = errors();
  std::printf("refined from the wrong calibration: %d poses ok, position RMS %.2f mm\n", refined.ok,
              1e3 * refined.position_rms_m);
  EXPECT_EQ(refined.ok, 20);
  EXPECT_LT(refined.position_rms_m, 0.005);
}

}  // namespace
}  // namespace irloc
