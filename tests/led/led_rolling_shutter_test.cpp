// The LED source under a rolling shutter (issue 29's LED part): seven ceiling LEDs over an upward
// fisheye (host_sim/scenarios/led_ceiling_up.yaml's room), the default board's readout (48.5 us a
// row, 23.3 ms a frame), the robot turning at 90 deg/s while driving at 1 m/s. Each LED's spot is
// drawn from the pose of the row it lands in (the simulator's rolling-shutter spots); the pose
// must be the one at the frame's t_ns, as accurate as under a global shutter, with the motion
// within the frame known (the track's) or not (the first frame: fitted with the pose).

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "algo/markers/led/led_landmark_source.hpp"
#include "algo/source/rolling_shutter.hpp"
#include "host_sim/render/landmark_spots.hpp"
#include "tests/led/led_scene.hpp"

namespace irloc::led {
namespace {

constexpr std::int64_t kLineTimeNs = 48'500;

// The `up` mount preset (docs/conventions.md), 0.3 m above the base.
RigidTransform up_mount() {
  RigidTransform mount;
  mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation = Eigen::Vector3d(0, 0, 0.3);
  return mount;
}

LedLandmark ceiling_led(double x, double y) {
  LedLandmark led = test::led_at(x, y, 2.79);
  led.direction = Eigen::Vector3d(0, 0, -1);
  led.half_angle = 1.4;
  return led;
}

test::LedScene ceiling_scene() {
  test::LedScene scene;
  scene.camera.model = LensModel::equisolid;
  scene.camera.fx = scene.camera.fy = 260;
  scene.mount = up_mount();
  scene.scene_leds = {ceiling_led(1.6, 1.2), ceiling_led(3.1, 1.0), ceiling_led(4.3, 1.7), ceiling_led(2.2, 2.6),
                      ceiling_led(3.7, 2.9), ceiling_led(1.9, 3.9), ceiling_led(3.4, 4.2)};
  scene.base_xyz = {3.0, 2.4, 0};
  scene.yaw = 0.4;
  scene.intensity = 0.02;
  return scene;
}

Eigen::Isometry3d isometry(const RigidTransform& transform) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = transform.rotation;
  result.translation() = transform.translation;
  return result;
}

// The pair of one pose attempt at the scene's pose (the one at t_ns), every spot drawn from the
// pose of its row under `motion` (line_time_ns 0: a global shutter).
void render_rolling(const test::LedScene& scene, const FrameMotion& motion, std::int64_t line_time_ns,
                    test::RenderedPair& pair) {
  const sim::Scenario scenario = scene.scenario();
  const CameraModel camera(scene.camera);
  const RigidTransform truth = scene.world_from_base();
  const sim::CameraPoseAtRow at_row = [&](double row) {
    return isometry(pose_after(truth, row * static_cast<double>(line_time_ns) * 1e-9, motion) * scene.mount);
  };
  const auto pixels = static_cast<std::size_t>(scene.camera.width * scene.camera.height);
  test::SceneRadiance radiance{std::vector<float>(pixels), {}};
  sim::add_landmark_spots(scenario, camera, at_row, 1.0, radiance.on);
  radiance.off = radiance.on;  // always on
  test::expose_pair(scene, radiance, pair);
}

struct Outcome {
  SourceResult result;
  double position_error = 0, yaw_error = 0;
};

Outcome attempt(const test::LedScene& scene, const FrameMotion& motion, std::int64_t line_time_ns,
                std::optional<FrameMotion> known_motion, std::optional<MotionPrior> motion_prior = std::nullopt) {
  MarkerMap map;
  map.led_landmarks = scene.scene_leds;
  LedLandmarkSource source(SourceSetup{scene.camera, scene.mount, Dof::planar3, map, scene.bit_depth}, {});
  test::RenderedPair pair;
  render_rolling(scene, motion, line_time_ns, pair);
  SourceInput input{pair.on, &pair.off};
  input.line_time_ns = line_time_ns;
  input.motion = known_motion;
  input.motion_prior = motion_prior;
  Outcome outcome;
  source.process(input, outcome.result);
  const RigidTransform truth = scene.world_from_base();
  outcome.position_error = (outcome.result.world_from_base.translation - truth.translation).norm();
  outcome.yaw_error = std::abs(wrap_angle(rpy_from_rotation(outcome.result.world_from_base.rotation).yaw - scene.yaw));
  return outcome;
}

// Turning left at 90 deg/s along an arc at 1 m/s: within the 23 ms of a frame the image turns by
// 2 degrees and the robot travels 23 mm, so the rows see the LEDs from poses up to that far apart
// (several pixels of skew at the image's edge, where 0.2 px of centre noise is expected).
TEST(LedRollingShutter, PoseAtTheFramesTimeAsAccurateAsAGlobalShutter) {
  const FrameMotion motion{Eigen::Vector3d(1.0, 0, 0), 1.5707963267948966};
  for (const double yaw : {0.4, 2.0, -1.2}) {
    test::LedScene scene = ceiling_scene();
    scene.yaw = yaw;
    const Outcome global = attempt(scene, motion, 0, std::nullopt);
    ASSERT_TRUE(global.result.ok) << global.result.outcome;
    for (const bool motion_known : {false, true}) {
      const Outcome rolling = attempt(scene, motion, kLineTimeNs, motion_known ? std::optional(motion) : std::nullopt);
      ASSERT_TRUE(rolling.result.ok) << "yaw " << yaw << (motion_known ? ", motion known: " : ", motion unknown: ")
                                     << rolling.result.outcome;
      EXPECT_LT(rolling.position_error, std::max(2 * global.position_error, 0.002))
          << "yaw " << yaw << (motion_known ? ", motion known" : ", motion unknown");
      EXPECT_LT(rolling.yaw_error, std::max(2 * global.yaw_error, 0.002))
          << "yaw " << yaw << (motion_known ? ", motion known" : ", motion unknown");
      EXPECT_EQ(rolling.result.observations.size(), global.result.observations.size());
      // The track's motion is what a first pose before this frame is revised with
      // (Localizer::revised_previous); the frame's own is not.
      EXPECT_EQ(rolling.result.motion_from_track.has_value(), motion_known);
    }
  }
}

// After a gap the track did not bridge (200 ms), the motion before it (the robot kept its arc,
// its track exact to 0.02 m/s and rad/s) is the prior of the motion fitted with the pose
// (motion_prior_after_gap): the pose's covariance is then what that fit leaves of the motion, not
// the fastest robot's travel over the rows' mean time, and still covers the pose's error.
TEST(LedRollingShutter, AfterAGapTheMotionBeforeItIsThePriorOfTheFramesOwnMotion) {
  const FrameMotion motion{Eigen::Vector3d(1.0, 0, 0), 1.5707963267948966};
  const std::optional<MotionPrior> prior = motion_prior_after_gap(motion, 0.02 * 0.02, 0.02 * 0.02, 0.2, {});
  ASSERT_TRUE(prior.has_value());
  for (const double yaw : {0.4, 2.0, -1.2}) {
    test::LedScene scene = ceiling_scene();
    scene.yaw = yaw;
    const Outcome fresh = attempt(scene, motion, kLineTimeNs, std::nullopt);
    const Outcome after_gap = attempt(scene, motion, kLineTimeNs, std::nullopt, prior);
    ASSERT_TRUE(fresh.result.ok) << fresh.result.outcome;
    ASSERT_TRUE(after_gap.result.ok) << after_gap.result.outcome;
    const auto sigma = [](const SourceResult& result) {
      return std::sqrt(result.covariance(0, 0) + result.covariance(1, 1));
    };
    std::printf("yaw %.1f: fresh %.2f mm off, sigma %.2f mm; after the gap %.2f mm off, sigma %.2f mm, yaw %.3f deg "
                "off, sigma %.3f deg\n", yaw, 1e3 * fresh.position_error, 1e3 * sigma(fresh.result),
                1e3 * after_gap.position_error, 1e3 * sigma(after_gap.result), after_gap.yaw_error * 57.29578,
                std::sqrt(after_gap.result.covariance(5, 5)) * 57.29578);
    EXPECT_LT(sigma(after_gap.result), sigma(fresh.result) / 3) << "yaw " << yaw;
    EXPECT_LT(after_gap.position_error, 3 * sigma(after_gap.result)) << "yaw " << yaw;
    EXPECT_LT(after_gap.yaw_error, 3 * std::sqrt(after_gap.result.covariance(5, 5))) << "yaw " << yaw;
  }
}

}  // namespace
}  // namespace irloc::led
