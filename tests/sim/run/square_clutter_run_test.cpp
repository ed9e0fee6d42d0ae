// irloc-sim end to end on the square tape marker among retro-reflective clutter (room.clutter):
// small rendered fisheye scenes with strips and crescents beside and inside the square, replayed
// through irlocd by run_scenario as `irloc-sim run` does, scored against the renderer's truth.
// The full-resolution drives are host_sim/scenarios/square_clutter*.yaml (docs/square_markers.md).

#include <string>

#include <gtest/gtest.h>

#include "host_sim/run/simulation_run.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180;

// The goal's setting at 400 x 320 (the same equisolid lens, its image circle just fitting the
// height): a 2 m square 2 m above the camera, sensor noise, a lamp, and clutter that has cost
// poses (tests/square/square_clutter_test.cpp): a duct's strip parallel to the solid side just
// outside it, a strip parallel to a side inside the square, a strip beyond the opposite side,
// crescents a few centimetres off two sides. The robot turns on the spot at `centre`.
std::string clutter_scene(const std::string& centre) {
  return "seed: 5\nframes: 12\ncamera:\n  calibration:\n"
         "    image_width: 400\n    image_height: 320\n"
         "    camera_matrix: {rows: 3, cols: 3, data: [113.1, 0, 199.5, 0, 113.1, 159.5, 0, 0, 1]}\n"
         "    distortion_model: equisolid\n    distortion_coefficients: {rows: 1, cols: 0, data: []}\n"
         "  mount: {preset: up, xyz: [0.05, 0, 0.3]}\n"
         "trajectory: {type: spin, centre: " + centre + ", yaw: 0.4, rate: 2.0}\n"
         "led_ring:\n  types:\n    - {name: ir850_wide, intensity: 4.0, half_angle: 1.0}\n"
         "  rings:\n    - {type: ir850_wide, count: 8, radius: 0.025, tilt: 0.2}\n"
         "room:\n  ceiling_height: 2.3\n  ambient: 0.5\n"
         "  lamps:\n    - {centre: [0.3, 0.2], size: [0.6, 0.6], radiance: 200}\n"
         "  clutter:\n"
         "    - {kind: strip, centre: [0.1, -1.22], length: 1.8, width: 0.05, yaw: 0}\n"
         "    - {kind: strip, centre: [0.6, 0.1], length: 1.6, width: 0.05, yaw: 1.5708}\n"
         "    - {kind: strip, centre: [-1.18, 0.0], length: 2.2, width: 0.05, yaw: 1.5708}\n"
         "    - {kind: crescent, centre: [0.3, 1.15], radius: 0.10, facing: -1.5708}\n"
         "    - {kind: crescent, centre: [1.2, -0.4], radius: 0.12, facing: 3.1416}\n"
         "map:\n  square_markers:\n    - name: hall\n"
         "      corners: [[-1, -1, 2.3], [1, -1, 2.3], [1, 1, 2.3], [-1, 1, 2.3]]\n"
         "metrics: {gross_position: 0.05, gross_yaw: 0.0175}\n";
}

// Under the square's centre and near a corner of the 4 m x 4 m area (the square far off the axis
// and small: where clutter cost the most frames), every pose attempt sees the whole square, is
// posed by the square path and lies within the goal's accuracy.
TEST(SquareClutterRun, ClutterAroundTheSquareCostsNoPose) {
  for (const std::string centre : {"[0.1, -0.2]", "[1.7, -1.6]"}) {
    SCOPED_TRACE(centre);
    test::TempDir dir;
    const Scenario scenario = parse_scenario(clutter_scene(centre), "clutter.yaml");
    ASSERT_EQ(scenario.room.clutter.size(), 5u);
    const RunOutputs outputs = run_scenario(scenario, dir.path());
    const Metrics& m = outputs.metrics;
    EXPECT_EQ(m.attempts, 6u);
    EXPECT_EQ(m.attempts_with_square_in_view, 6u);
    EXPECT_EQ(m.poses_with_square_in_view, 6u);
    EXPECT_EQ(m.poses_ok, 6u);
    EXPECT_EQ(m.poses_by_source.count("square") ? m.poses_by_source.at("square") : 0u, m.poses_ok);
    EXPECT_EQ(m.gross_errors, 0u);
    EXPECT_LT(m.position.rmse, 0.015);
    EXPECT_LT(m.yaw.rmse, 0.5 * kDegree);
  }
}

}  // namespace
}  // namespace irloc::sim
