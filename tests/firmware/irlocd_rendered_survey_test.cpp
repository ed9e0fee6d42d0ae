// irlocd --survey end to end on rendered frames: a 2 x 3 grid of dot markers installed off its
// drawing by up to 0.1 m and 3 degrees, surveyed in three passes at 640 x 480; the written map
// against the truth, and the poses during the survey against the true trajectory.

#include <cmath>
#include <fstream>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "algo/geometry/pose.hpp"
#include "hal/config/map_file.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

constexpr const char* kDrawing = R"(dot_markers:
  - {id: 1000, origin: [0.0, 0.0, 2.6], yaw: 0.0, fixed: true}
  - {id: 1037, origin: [1.2, 0.0, 2.6], yaw: 0.0}
  - {id: 1074, origin: [0.0, 1.2, 2.6], yaw: 0.0}
  - {id: 1111, origin: [1.2, 1.2, 2.6], yaw: 0.0}
  - {id: 1148, origin: [0.0, 2.4, 2.6], yaw: 0.0}
  - {id: 1185, origin: [1.2, 2.4, 2.6], yaw: 0.0}
)";

constexpr const char* kScenario = R"(seed: 21
frames: 200
camera:
  calibration:
    image_width: 640
    image_height: 480
    camera_matrix: {rows: 3, cols: 3, data: [400, 0, 319.5, 0, 400, 239.5, 0, 0, 1]}
    distortion_model: plumb_bob
    distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}
  mount: {preset: up, xyz: [0.05, 0, 0.3]}
  frame_rate: 10
  exposure: 0.002
robot:
  dof: 3
trajectory:
  type: waypoints
  points: [[0.6, -0.4], [0.6, 2.8], [0.6, -0.4], [0.6, 2.8]]
  speed: 0.5
led_ring:
  types:
    - {name: ir850_wide, intensity: 0.2, half_angle: 0.6}
  rings:
    - {type: ir850_wide, count: 12, radius: 0.025, tilt: 0.35}
room:
  ceiling_height: 2.6
map:
  dot_markers:
    - {id: 1000, origin: [0.0, 0.0, 2.6], yaw: 0.0}
    - {id: 1037, origin: [1.27, -0.06, 2.6], yaw: 0.04}
    - {id: 1074, origin: [-0.08, 1.25, 2.6], yaw: -0.05}
    - {id: 1111, origin: [1.16, 1.29, 2.6], yaw: 0.03}
    - {id: 1148, origin: [0.05, 2.32, 2.6], yaw: -0.02}
    - {id: 1185, origin: [1.3, 2.45, 2.6], yaw: 0.05}
render:
  supersampling: 1
)";

TEST(IrlocdRenderedSurvey, ThreePassesPlaceEveryMarkerAndPoseEveryFrameNearTheTruth) {
  test::TempDir dir;
  std::ofstream(dir / "scenario.yaml") << kScenario;
  std::ofstream(dir / "drawing.yaml") << kDrawing;
  const std::filesystem::path dataset = dir / "dataset";
  std::map<std::uint64_t, sim::TruthRow> truth;
  for (const sim::TruthRow& row : sim::render_dataset(sim::load_scenario(dir / "scenario.yaml"), dataset)) truth[row.seq] = row;
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
  // The issue's 5 mm and 0.2 deg are for 1280 x 960 (docs/survey.md); this quarter of the pixels
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
