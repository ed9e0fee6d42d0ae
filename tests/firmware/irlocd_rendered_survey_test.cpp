// irlocd --survey end to end on rendered frames: a 2 x 3 grid of dot markers (the corridor of
// tests/survey/corridor.hpp, 1.2 m apart) installed off its drawing by up to 0.1 m and 3 degrees,
// surveyed in three passes at 640 x 480; the written map against the truth, and the poses during
// the survey against the true trajectory.

#include <cmath>
#include <fstream>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "algo/geometry/pose.hpp"
#include "hal/config/map_file.hpp"
#include "hal/files/map_file_writer.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/firmware/rendered_robot_scenario.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"
#include "tests/survey/corridor.hpp"

namespace irloc {
namespace {

// 200 frames at 10 fps, 640 x 480: three passes along the grid, under the markers as installed
// (the drawing: test::corridor_drawing(6, 1.2)).
test::ScenarioText installed_grid_scenario() {
  test::ScenarioText text = test::rendered_robot_scenario(400, "[0, 0, 0, 0, 0]", 10);
  text.seed = 21;
  text.frames = 200;
  text.trajectory = "  type: waypoints\n  points: [[0.6, -0.4], [0.6, 2.8], [0.6, -0.4], [0.6, 2.8]]\n  speed: 0.5\n";
  text.map = "  dot_markers:\n"
             "    - {id: 1000, origin: [0.0, 0.0, 2.6], yaw: 0.0}\n"
             "    - {id: 1037, origin: [1.27, -0.06, 2.6], yaw: 0.04}\n"
             "    - {id: 1074, origin: [-0.08, 1.25, 2.6], yaw: -0.05}\n"
             "    - {id: 1111, origin: [1.16, 1.29, 2.6], yaw: 0.03}\n"
             "    - {id: 1148, origin: [0.05, 2.32, 2.6], yaw: -0.02}\n"
             "    - {id: 1185, origin: [1.3, 2.45, 2.6], yaw: 0.05}\n";
  return text;
}

TEST(IrlocdRenderedSurvey, ThreePassesPlaceEveryMarkerAndPoseEveryFrameNearTheTruth) {
  test::TempDir dir;
  hal::write_marker_map(dir / "drawing.yaml", test::corridor_drawing(6, 1.2));
  const std::filesystem::path dataset = dir / "dataset";
  std::map<std::uint64_t, sim::TruthRow> truth;
  const sim::Scenario scenario = sim::parse_scenario(installed_grid_scenario().yaml(), "scenario.yaml");
  for (const sim::TruthRow& row : sim::render_dataset(scenario, dataset)) truth[row.seq] = row;
  std::string config = test::read_text(dataset / "config.yaml");
  config.replace(config.find("map: map.yaml"), 13, "map: " + (dir / "drawing.yaml").string());
  std::ofstream(dataset / "survey_config.yaml") << config;

  const test::ProcessResult run = test::run_to_end(
      {IRLOCD_PATH, "--config", (dataset / "survey_config.yaml").string(), "--camera", "dir:" + dataset.string(), "--serial",
       "none", "--pose-csv", (dir / "pose.csv").string(), "--survey", (dir / "surveyed.yaml").string()},
      dir / "stderr.txt");
  ASSERT_EQ(run.status, 0) << run.stderr_text;
  EXPECT_THAT(run.stderr_text, ::testing::Not(::testing::HasSubstr("survey: marker")));

  const MarkerMap surveyed = hal::load_marker_map(dir / "surveyed.yaml");
  const MarkerMap installed = hal::load_marker_map(dataset / "map.yaml");
  ASSERT_EQ(surveyed.dot_markers.size(), installed.dot_markers.size());
  double worst_mm = 0, worst_deg = 0;
  for (const DotMarker& real : installed.dot_markers) {
    const DotMarker* estimate = surveyed.find_dot_marker(real.id);
    ASSERT_NE(estimate, nullptr) << real.id;
    worst_mm = std::max(worst_mm, 1e3 * (estimate->origin - real.origin).norm());
    worst_deg = std::max(worst_deg, std::abs(wrap_angle(estimate->yaw - real.yaw)) * 180 / M_PI);
  }
  std::printf("surveyed map: every marker within %.2f mm, %.3f deg of the truth\n", worst_mm, worst_deg);
  // The 5 mm and 0.2 deg are for 1280 x 960 (docs/survey.md); this quarter of the pixels
  // gives about 4.4 mm and 0.19 deg.
  EXPECT_LT(worst_mm, 8.0);
  EXPECT_LT(worst_deg, 0.4);

  // During the survey: no pose off by more than 1 cm, however early.
  int posed = 0;
  double sum_squares = 0;
  const std::vector<PoseEstimate> poses = sim::read_pose_csv(dir / "pose.csv");
  for (const PoseEstimate& pose : poses) {
    if (!pose.ok) continue;
    const sim::TruthRow& row = truth.at(pose.seq);
    const double error = std::hypot(pose.x - row.x, pose.y - row.y);
    EXPECT_LT(error, 0.01) << "frame " << pose.seq;
    sum_squares += error * error;
    ++posed;
  }
  std::printf("poses during the survey: %d of %zu attempts, RMSE %.2f mm\n", posed, poses.size(),
              1e3 * std::sqrt(sum_squares / std::max(posed, 1)));
  EXPECT_GE(posed, static_cast<int>(0.9 * static_cast<double>(poses.size())));
}

}  // namespace
}  // namespace irloc
