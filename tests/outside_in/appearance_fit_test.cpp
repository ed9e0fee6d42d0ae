// The appearance fit (appearance_fit.hpp) and the source with it, on rendered wall-camera scenes of
// issue 27's robot: light grey, brighter than the floor, a dark strip over the lower 35 % of its
// front (host_sim/scenarios/outside_in_light_robot.yaml's look). Its faces match the lighter tiles
// and its sides pass for shadow: the foreground holds only parts of it.
#include "algo/markers/outside_in/appearance_fit.hpp"

#include <array>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "tests/outside_in/outside_in_drive.hpp"

namespace irloc::test {
namespace {

using namespace irloc::outside_in;  // the fit under test

constexpr double kDeg = std::numbers::pi / 180;
const sim::RobotLook kLightGreyWithStrip{205, 185, 165, 175, 45, 0, 0.35};

// The goal room's camera and box model, its background learned from frames of the empty floor.
struct LearnedRoom {
  WallCamera camera;
  SceneRenderer renderer{camera};
  CameraModel model{camera.intrinsics};
  BoxSilhouette box{model, camera.world_from_camera().inverse(), BoxBody{}};
  AdaptiveBackground background{[] {
    AdaptiveBackgroundConfig config = OutsideInConfig{}.background;
    config.width = 640;
    config.height = 480;
    return config;
  }()};
  std::vector<std::uint8_t> foreground = std::vector<std::uint8_t>(640 * 480);

  LearnedRoom() {
    renderer.look = kLightGreyWithStrip;
    for (int i = 0; i < 20; ++i) apply(SceneState{});
  }
  // Renders the scene, updates the background with it; the frame.
  const std::vector<std::uint8_t>& apply(const SceneState& scene) {
    FrameTruth truth;
    const auto& pixels = renderer.render(scene, truth);
    background.apply(ImageView8(pixels.data(), 640, 480), MutableImageView8(foreground.data(), 640, 480), ProtectedRects{});
    return pixels;
  }
};

// The robot 3.3-4.7 m out, at headings all round, started 4 cm and 3 degrees off: within 2 cm
// and 1 degree (modulo the half turn), taken as the robot, in bounded work. The cost is flat within
// a pixel's shift of the box (about 1 cm on the floor 4.7 m out): 0-15 mm, 0.1-0.5 degrees.
TEST(AppearanceFitter, FromAStartNearTheRobotEndsOnIt) {
  LearnedRoom room;
  AppearanceFitter fitter(room.box, 640, 480);
  for (double x : {3.3, 4.0, 4.7})
    for (double yaw_deg : {0.0, 40.0, 95.0, 150.0}) {
      const FloorPose truth{x, 0.4 * std::sin(x), yaw_deg * kDeg};
      SceneState scene;
      scene.robot = truth;
      FrameTruth frame_truth;
      const auto& pixels = room.renderer.render(scene, frame_truth);
      const FloorPose start{truth.x + 0.03, truth.y - 0.025, truth.yaw + 3 * kDeg};
      const AppearanceFit fit = fitter.refine(ImageView8(pixels.data(), 640, 480), room.background, start);
      ASSERT_TRUE(fit.ok);
      EXPECT_LE(fit.evaluations, AppearanceFitter::kMaxEvaluations);
      const double position = std::hypot(fit.pose.x - truth.x, fit.pose.y - truth.y);
      const double heading = std::abs(std::remainder(fit.pose.yaw - truth.yaw, std::numbers::pi));
      std::printf("robot at (%.1f, %.2f, %.0f deg): %.1f mm, %.2f deg off, box outliers %.3f, around %.3f, contrast %.2f\n",
                  truth.x, truth.y, yaw_deg, 1000 * position, heading / kDeg, fit.box_outlier_fraction,
                  fit.around_outlier_fraction, fit.contrast_fraction);
      EXPECT_LT(position, 0.02) << "robot at x " << x << ", yaw " << yaw_deg;
      EXPECT_LT(heading, 1 * kDeg) << "robot at x " << x << ", yaw " << yaw_deg;
      EXPECT_TRUE(fit.explains_robot()) << "robot at x " << x << ", yaw " << yaw_deg;
    }
}

// A start 7 cm off ends in a minimum beside the robot's that still explains it (71 mm off); with a
// second start near the robot, whichever comes first, the robot's minimum wins.
TEST(AppearanceFitter, OfTwoStartsTheOneEndingInTheRobotsMinimumWins) {
  LearnedRoom room;
  AppearanceFitter fitter(room.box, 640, 480);
  const FloorPose truth{4.7, 0.4 * std::sin(4.7), 40 * kDeg};
  SceneState scene;
  scene.robot = truth;
  FrameTruth frame_truth;
  const auto& pixels = room.renderer.render(scene, frame_truth);
  const ImageView8 frame(pixels.data(), 640, 480);
  const FloorPose aside{truth.x + 0.05, truth.y + 0.05, truth.yaw};
  const FloorPose near{truth.x - 0.013, truth.y + 0.017, truth.yaw - 2 * kDeg};
  const auto off_mm = [&](const AppearanceFit& fit) { return 1000 * std::hypot(fit.pose.x - truth.x, fit.pose.y - truth.y); };
  const AppearanceFit alone = fitter.refine(frame, room.background, aside);
  std::printf("from the start aside alone: %.1f mm off, box outliers %.3f\n", off_mm(alone), alone.box_outlier_fraction);
  ASSERT_TRUE(alone.explains_robot());
  ASSERT_GT(off_mm(alone), 40);
  for (const std::array<FloorPose, 2>& starts : {std::array{aside, near}, std::array{near, aside}}) {
    const AppearanceFit fit = fitter.refine(frame, room.background, starts);
    std::printf("from both starts: %.1f mm off, %d costs\n", off_mm(fit), fit.evaluations);
    EXPECT_TRUE(fit.explains_robot());
    EXPECT_LT(off_mm(fit), 20);
    EXPECT_LT(std::abs(std::remainder(fit.pose.yaw - truth.yaw, std::numbers::pi)), 1 * kDeg);
    EXPECT_LE(fit.evaluations, AppearanceFitter::kMaxStarts * AppearanceFitter::kMaxEvaluations);
  }
  const std::array<FloorPose, 3> too_many{aside, near, truth};
  EXPECT_THROW(fitter.refine(frame, room.background, too_many), std::invalid_argument);
}

// A start on the empty floor, or on a robot a metre away: nothing there is the box.
TEST(AppearanceFitter, TheEmptyFloorIsNotTakenForTheRobot) {
  LearnedRoom room;
  AppearanceFitter fitter(room.box, 640, 480);
  SceneState scene;
  scene.robot = FloorPose{4.0, 0.5, 30 * kDeg};
  FrameTruth truth;
  const auto& pixels = room.renderer.render(scene, truth);
  for (const FloorPose& start : {FloorPose{4.0, -0.6, 30 * kDeg}, FloorPose{3.0, 0.5, 120 * kDeg}, FloorPose{5.2, 0.0, 0}}) {
    const AppearanceFit fit = fitter.refine(ImageView8(pixels.data(), 640, 480), room.background, start);
    EXPECT_FALSE(fit.explains_robot()) << "start (" << start.x << ", " << start.y << "): contrast " << fit.contrast_fraction
                                       << ", box outliers " << fit.box_outlier_fraction;
  }
}

// The goal scenario's drive, person, lamp steps and sun with issue 27's robot: no pose before the
// appearance fit (docs/outside_in.md, "Robots of every look"); with it, posed at the goal's
// accuracy, never off the robot or flipped.
TEST(OutsideInSource, ALightGreyRobotTheForegroundSeesInPartsIsPosedByItsAppearance) {
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera);
  renderer.look = kLightGreyWithStrip;
  const ScenarioScore score = run_scenario(rig, renderer, 140, 35, goal_scene);
  expect_scenario_goal(score, "light grey robot, goal scenario", 0.30);
}

// Issue 27's robot drives once round the goal's loop (19 s: its track's branch from the travel, both
// end faces seen), leaves the view, and after 3 s is back elsewhere, facing the camera, and turns in
// place: a new track that drives 0.5 m, too little for a branch from travel. Its end faces tell it:
// posed, none flipped.
TEST(OutsideInSource, ARobotBackInViewIsToldItsFrontByItsEndFaces) {
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera);
  renderer.look = kLightGreyWithStrip;
  constexpr int kBack = 220, kEnd = 260;
  const auto scene_at = [](int i) {
    SceneState scene;
    if (i < 190) scene.robot = ellipse_pose(i / 10.0);
    const int k = i - kBack;  // 0.5 m toward the camera, then a turn in place
    if (k >= 0) scene.robot = FloorPose{4.0 - 0.05 * std::min(k, 10), -0.4, std::numbers::pi + 0.05 * std::max(k - 10, 0)};
    return scene;
  };
  const ScenarioScore score = run_scenario(rig, renderer, kEnd, kBack, scene_at);
  std::printf("robot back in view facing the camera: %d poses of frames %d-%d, worst heading %.1f deg, %d flipped\n",
              score.eligible_posed, kBack, kEnd - 1, score.worst_heading / kDeg, score.flips);
  EXPECT_EQ(score.flips, 0);
  EXPECT_EQ(score.far_poses, 0);
  EXPECT_EQ(score.poses_without_robot, 0);
  EXPECT_LT(score.worst_heading, 10 * kDeg);  // bench_outside_goal's gross
  EXPECT_GE(score.eligible_posed, 15);  // 0 without the end faces
}

}  // namespace
}  // namespace irloc::test
