// The simulator's parts for LED scenes: the trajectory's sway (roll, pitch, heave for dof 6
// robots) and the point-spread spots' brightness.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "algo/geometry/pose.hpp"
#include "algo/markers/led/led_detector.hpp"
#include "host_sim/render/led_family_frames.hpp"
#include "host_sim/scenario/led_scene_family.hpp"
#include "host_sim/tools/led_placement.hpp"
#include "host_sim/render/renderer.hpp"
#include "host_sim/scenario/trajectory.hpp"
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

TEST(LedSimulation, RendererImagesLedsAsSpotsCarryingTheirLight) {
  // An LED straight ahead of the camera: the rendered frame's sum is I / d^2 x pixels per
  // steradian (f^2 on the axis), and it equals the spots the LED tests draw directly.
  test::LedScene scene;
  scene.camera.width = 160;  // small: ray tracing every pixel is slow under the sanitizers
  scene.camera.height = 120;
  scene.camera.fx = scene.camera.fy = 125;
  scene.camera.cx = 79.5;
  scene.camera.cy = 59.5;
  scene.scene_leds = {test::led_at(4.1, 0, 0.5)};
  const Scenario scenario = scene.scenario();
  const CameraModel camera(scene.camera);
  const Renderer renderer(scenario, camera);
  std::vector<float> radiance(160 * 120);
  renderer.render(0, false, radiance);
  const test::SceneRadiance spots = test::render_radiance(scene);
  double sum = 0, difference = 0;
  for (std::size_t i = 0; i < radiance.size(); ++i) {
    sum += radiance[i];
    difference = std::max(difference, static_cast<double>(std::abs(radiance[i] - spots.off[i])));
  }
  const double expected = scene.intensity / (4.0 * 4.0) * 125.0 * 125.0;
  EXPECT_NEAR(sum, expected, 1e-3 * expected);
  EXPECT_LT(difference, 1e-6 * expected);
}

TEST(LedSimulation, SpotsDimWithTheSquareOfDistance) {
  auto spot_sum = [](double distance) {
    test::LedScene scene;
    scene.scene_leds = {test::led_at(0.1 + distance, 0, 0.5)};
    const test::SceneRadiance spots = test::render_radiance(scene);
    double sum = 0;
    for (const float value : spots.off) sum += value;
    return sum;
  };
  EXPECT_NEAR(spot_sum(2.0) / spot_sum(6.0), 9.0, 9e-3);
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

// The family's renderer vouches for a spurious always-on point in view as it does for an LED
// (LedFamilyPair::stray, what bench_led_goal's oracle counts among the bright points): wall under
// dof 4, seed 41, scene 23, two LEDs and a spurious point on the wall; the detector finds a spot at
// each.
TEST(LedSimulation, FamilyRendererVouchesForASpuriousPointInView) {
  const LedFamilyScene scene = draw_led_family_scene(41, LedFamilyClass::wall_dof4, 23);
  const led::LedSourceConfig config;
  LedFamilyPair pair;
  render_led_family_pair(scene, 0, config.threshold, pair);
  ASSERT_EQ(pair.visible.size(), 2u);
  ASSERT_EQ(pair.stray.size(), 1u);
  led::LedDetector detector(scene.camera.width, scene.camera.height, scene.bit_depth, config);
  led::LedDetectionList detections;
  led::LedGlareList glare;
  led::LedDetectionCounters counters;
  detector.detect(pair.on.image, &pair.off.image, detections, glare, counters);
  std::vector<Eigen::Vector2d> spots{pair.stray[0]};
  for (const VisibleLed& led : pair.visible) spots.push_back(led.pixel);
  for (const Eigen::Vector2d& spot : spots) {
    EXPECT_TRUE(std::any_of(detections.begin(), detections.end(),
                            [&](const led::LedDetection& d) { return (d.pixel - spot).norm() < 0.5; }))
        << "no detection at (" << spot.transpose() << ")";
  }
}

}  // namespace
}  // namespace irloc::sim
