// The simulator's parts for LED scenes: the trajectory's sway (roll, pitch, heave for dof 6
// robots) and the point-spread spots' brightness.

#include <gtest/gtest.h>

#include <cmath>

#include "algo/geometry/pose.hpp"
#include "host_sim/led_placement.hpp"
#include "host_sim/trajectory.hpp"
#include "tests/led/led_scene.hpp"

namespace irloc::sim {
namespace {

TEST(LedSimulation, SwayRollsPitchesAndHeavesWithinItsAmplitudes) {
  TrajectorySpec spec;
  spec.kind = TrajectoryKind::static_pose;
  spec.pose = {1, 2, 0.5};
  spec.sway_roll = 0.05;
  spec.sway_pitch = 0.04;
  spec.sway_heave = 0.01;
  spec.sway_period = 2;
  const Trajectory trajectory(spec);
  double max_roll = 0, max_pitch = 0, max_heave = 0;
  for (int k = 0; k < 400; ++k) {
    const Eigen::Isometry3d pose = trajectory.t_w_b(0.01 * k);
    const RollPitchYaw rpy = rpy_from_rotation(pose.linear());
    max_roll = std::max(max_roll, std::abs(rpy.roll));
    max_pitch = std::max(max_pitch, std::abs(rpy.pitch));
    max_heave = std::max(max_heave, std::abs(pose.translation().z()));
    EXPECT_NEAR(rpy.yaw, 0.5, 1e-12);
    EXPECT_NEAR(pose.translation().x(), 1, 1e-12);
  }
  EXPECT_LE(max_roll, 0.05 + 1e-12);
  EXPECT_GT(max_roll, 0.045);
  EXPECT_LE(max_pitch, 0.04 + 1e-12);
  EXPECT_GT(max_pitch, 0.035);
  EXPECT_LE(max_heave, 0.01 + 1e-12);
  EXPECT_GT(max_heave, 0.008);
}

TEST(LedSimulation, SpotCarriesTheLedsLightAndDimsWithTheSquareOfDistance) {
  // Sum of the spot's radiance over the image: I / d^2 x pixels per steradian (f^2 on the axis).
  auto spot_sum = [](double distance) {
    test::LedScene scene;
    scene.scene_leds = {test::led_at(0.1 + distance, 0, 0.5)};  // straight ahead of the camera
    const Scenario scenario = scene.scenario();
    const CameraModel camera(scene.camera);
    const Renderer renderer(scenario, camera);
    std::vector<float> radiance(640 * 480);
    renderer.render(0, false, radiance);
    double sum = 0;
    for (const float value : radiance) sum += value;
    return std::make_pair(sum, scene.intensity / (distance * distance) * 500.0 * 500.0);
  };
  for (const double distance : {2.0, 4.0}) {
    const auto [sum, expected] = spot_sum(distance);
    EXPECT_NEAR(sum, expected, 1e-3 * expected) << "at " << distance << " m";
  }
}

TEST(LedSimulation, PlacementMapGivesNoPoseNearTheWallsAndErrorsInProportionToTheNoise) {
  const Scenario scenario = load_scenario(IRLOC_SOURCE_DIR "/host_sim/scenarios/led_paper_placement.yaml");
  const HeatMap map = led_position_error_map(scenario, 0.5, 12, 0.17);
  const HeatMap noisier = led_position_error_map(scenario, 0.5, 12, 0.34);
  ASSERT_EQ(map.columns, 12);
  ASSERT_EQ(map.rows, 12);
  auto at = [](const HeatMap& m, int column, int row) { return m.values[static_cast<std::size_t>(row * m.columns + column)]; };
  // The room's centre sees LEDs at every heading; 0.25 m from a wall the 1.5 m high LEDs are
  // above the camera's field when it faces that wall.
  EXPECT_TRUE(std::isfinite(at(map, 5, 5)));
  EXPECT_GT(at(map, 5, 5), 0.5);   // mm
  EXPECT_LT(at(map, 5, 5), 30.0);
  EXPECT_FALSE(std::isfinite(at(map, 0, 5)));
  EXPECT_NEAR(at(noisier, 5, 5), 2 * at(map, 5, 5), 1e-6 * at(map, 5, 5));
}

}  // namespace
}  // namespace irloc::sim
