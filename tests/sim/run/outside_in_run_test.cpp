// irloc-sim on outside-in scenarios (kind: outside_in): a small wall-camera scene rendered,
// replayed through irlocd in `mode: outside_in`, scored against the renderer's truth; the metrics
// on hand-made poses; a floor reference off the tile corners refused with the file and field; the
// robot's look read, drawn, and refused naming its key.

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host_sim/metrics/outside_in_metrics.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/outside_in_renderer.hpp"
#include "host_sim/run/simulation_run.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::sim {
namespace {

using ::testing::HasSubstr;

// A 320 x 240 wall camera 2.4 m up; the robot drives straight away from it, 2.2 - 5.4 m, with one
// lamp step. The first 35 frames learn the background (the robot is in view from the start).
std::string small_scene(const std::string& trajectory, int frames = 80,
                        const std::string& floor_reference = "[[2.5, 1.0], [4.5, 1.0], [4.5, -1.0], [2.5, -1.0]]") {
  return "kind: outside_in\nseed: 3\nframes: " + std::to_string(frames) +
         "\ncamera:\n  calibration:\n    image_width: 320\n    image_height: 240\n"
         "    camera_matrix: {rows: 3, cols: 3, data: [250, 0, 159.5, 0, 250, 119.5, 0, 0, 1]}\n"
         "    distortion_model: plumb_bob\n    distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n"
         "  frame_rate: 10\n  wall: {position: [0, 0], height: 2.4, pitch_deg: 38}\n"
         "floor_reference: " + floor_reference +
         "\nrobot:\n  body: {length: 0.60, width: 0.40, height: 0.35}\ntrajectory:\n" + trajectory +
         "light_steps:\n  - {frame: 55, lamp: 0.75}\nmetrics:\n  warm_up_frames: 35\n";
}

const std::string kStraightAway = "  type: waypoints\n  points: [[2.2, -0.5], [5.4, -0.5]]\n  speed: 0.4\n";

TEST(OutsideInRun, PosesTheRobotOnItsPathThroughIrlocd) {
  test::TempDir dir;
  const Scenario scenario = parse_scenario(small_scene(kStraightAway), "small.yaml");
  ASSERT_TRUE(scenario.outside_in);
  const RunOutputs outputs = run_scenario(scenario, dir.path());
  ASSERT_TRUE(outputs.outside_in);
  const OutsideInMetrics& m = *outputs.outside_in;
  EXPECT_EQ(m.frames, 80);
  EXPECT_EQ(m.eligible, 45);  // every frame after the warm-up: the robot stays whole in view
  EXPECT_GE(m.pose_rate, 0.95);
  EXPECT_LE(m.position_rms, 0.030);  // half the goal's resolution
  EXPECT_LE(m.heading_rms_deg, 3.0);
  EXPECT_EQ(m.poses_out_of_view, 0);
  EXPECT_EQ(m.poses_off_robot, 0);
  EXPECT_EQ(m.heading_flips, 0);
  EXPECT_THAT(test::read_text(dir.path() / "dataset" / "config.yaml"), HasSubstr("mode: outside_in"));
  EXPECT_THAT(test::read_text(dir.path() / "outside_in_metrics.json"), HasSubstr("\"eligible_frames\": 45"));
  for (const char* name : {"metrics.json", "trajectory.png", "errors.png", "pose.csv", "dataset/truth.csv"}) {
    EXPECT_GT(std::filesystem::file_size(dir.path() / name), 0u) << name;
  }
}

TEST(OutsideInRun, NoPoseAfterTheRobotLeavesTheView) {
  test::TempDir dir;
  // Away from the wall, then sideways out of the image and on, out of view, for 3 s.
  const std::string trajectory = "  type: waypoints\n  points: [[2.2, -0.3], [4.0, -0.3], [4.0, -6.0]]\n  speed: 0.6\n";
  const RunOutputs outputs = run_scenario(parse_scenario(small_scene(trajectory, 110), "leave.yaml"), dir.path());
  const OutsideInMetrics& m = *outputs.outside_in;
  EXPECT_LT(m.eligible, 110 - 35 - 20);  // the truth has the robot out of view at the end
  // Each fit's heading weighs by its heading_per_px, which at 320 x 240 is twice that at
  // 640 x 480: about half the frames are heading_uncertain, no pose (0.8 before that).
  EXPECT_GE(m.pose_rate, 0.5);
  EXPECT_EQ(m.poses_off_robot, 0);
  // The goal counts a pose while a corner of the box is off the image: the source gives one as the
  // corner crosses the edge (frame 75 of this drive, 1 mm off), none after it.
  EXPECT_LE(m.poses_out_of_view, 1);
  std::uint64_t last_pose = 0;
  for (const PoseEstimate& pose : read_pose_csv(dir.path() / "pose.csv")) {
    if (pose.ok) last_pose = pose.seq;
  }
  EXPECT_LE(last_pose, 76u);
}

TEST(OutsideInRun, MetricsCountEligibleFramesOffPosesAndFlips) {
  const auto truth_at = [](std::uint64_t seq, bool in_view, double hidden) {
    return OutsideInTruth{TruthRow{seq, 0, false, 3.0, 0.0, 0, 0, 0, 0.5}, in_view, hidden};
  };
  const std::vector<OutsideInTruth> truth = {truth_at(0, true, 0),   truth_at(1, true, 0),    truth_at(2, true, 0.1),
                                             truth_at(3, true, 0.5), truth_at(4, false, 0),  truth_at(5, true, 0)};
  const auto pose_at = [](std::uint64_t seq, double x, double yaw) {
    PoseEstimate pose;
    pose.seq = seq;
    pose.ok = true;
    pose.x = x;
    pose.yaw = yaw;
    return pose;
  };
  // 0: warm-up; 1: 30 mm off; 2: 40 mm off; 3: over 20 % hidden, flipped; 4: out of view; 5: none.
  const std::vector<PoseEstimate> poses = {pose_at(0, 3.0, 0.5), pose_at(1, 3.03, 0.5), pose_at(2, 3.04, 0.5),
                                           pose_at(3, 3.0, 0.5 + 3.0), pose_at(4, 3.0, 0.5)};
  MetricsSpec thresholds;
  thresholds.gross_position = 0.15;
  thresholds.gross_yaw = 1.5;
  thresholds.warm_up_frames = 1;
  const OutsideInMetrics m = compute_outside_in_metrics(truth, poses, thresholds);
  EXPECT_EQ(m.eligible, 3);  // 1, 2, 5
  EXPECT_EQ(m.eligible_posed, 2);
  EXPECT_NEAR(m.position_rms, std::sqrt((0.03 * 0.03 + 0.04 * 0.04) / 2), 1e-9);
  EXPECT_NEAR(m.position_max, 0.04, 1e-9);
  EXPECT_EQ(m.poses_out_of_view, 1);
  EXPECT_EQ(m.heading_flips, 1);
  EXPECT_EQ(m.poses_off_robot, 0);
}

TEST(OutsideInRun, AFloorReferenceOffTheTileCornersIsRefused) {
  const std::string message = test::input_error_message([] {
    parse_scenario(small_scene(kStraightAway, 80, "[[2.5, 1.0], [4.5, 1.0], [4.5, -1.0], [2.6, -1.0]]"), "bad.yaml");
  });
  EXPECT_THAT(message, HasSubstr("bad.yaml"));
  EXPECT_THAT(message, HasSubstr("floor_reference"));
  EXPECT_THAT(message, HasSubstr("corner 3 is not a tile corner"));
}

std::string with_look(const std::string& look) {
  std::string text = small_scene(kStraightAway);
  const std::string body = "  body: {length: 0.60, width: 0.40, height: 0.35}\n";
  return text.replace(text.find(body), body.size(), body + look);
}

TEST(OutsideInRun, TheRobotsLookIsReadAndDrawnFaceByFace) {
  const Scenario scenario = parse_scenario(
      with_look("  look: {top: 210, front: 190, back: 170, sides: 180, front_strip: {shade: 40, from: 0, to: 0.4}}\n"),
      "look.yaml");
  const RobotLook& look = scenario.outside_in->look;
  EXPECT_EQ(look.top, 210);
  EXPECT_EQ(look.sides, 180);
  EXPECT_EQ(look.strip_to, 0.4);
  EXPECT_EQ(parse_scenario(small_scene(kStraightAway), "dark.yaml").outside_in->look.top, RobotLook{}.top);

  // The robot 3 m out, its front (+x) facing the camera: the strip below 40 % of its height, the
  // front's own shade above it, the top above that (no exposure change, no noise).
  WallCamera camera;
  camera.intrinsics = scenario.camera.intrinsics;
  SceneRenderer renderer(camera, outside_in::BoxBody{0.6, 0.4, 0.35});
  renderer.auto_exposure = false;
  renderer.noise_sigma = 0;
  renderer.look = look;
  SceneState scene;
  scene.robot = outside_in::FloorPose{3.0, 0.0, std::numbers::pi};
  FrameTruth truth;
  const std::vector<std::uint8_t>& pixels = renderer.render(scene, truth);
  const WallProjection view(camera);
  const auto grey_at = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector2d px = view.project(point);
    return int{pixels[static_cast<std::size_t>(std::lround(px.y())) * 320 + static_cast<std::size_t>(std::lround(px.x()))]};
  };
  EXPECT_EQ(grey_at({2.7, 0.0, 0.07}), 40);
  EXPECT_EQ(grey_at({2.7, 0.0, 0.25}), 190);
  EXPECT_EQ(grey_at({3.0, 0.0, 0.35}), 210);
}

TEST(OutsideInRun, ABadRobotLookIsRefusedNamingItsKey) {
  const auto message_of = [](const std::string& look) {
    return test::input_error_message([&] { parse_scenario(with_look(look), "look.yaml"); });
  };
  std::string message = message_of("  look: {top: 300}\n");
  EXPECT_THAT(message, HasSubstr("look.yaml"));
  EXPECT_THAT(message, HasSubstr("robot.look.top"));
  message = message_of("  look: {front_strip: {shade: 40, from: 0.5, to: 0.2}}\n");
  EXPECT_THAT(message, HasSubstr("robot.look.front_strip.to"));
  EXPECT_THAT(message, HasSubstr("must be above 'from'"));
  EXPECT_THAT(message_of("  look: {colour: 40}\n"), HasSubstr("robot.look.colour"));
  EXPECT_THAT(message_of("  look: {front_strip: {from: 0, to: 0.3}}\n"), HasSubstr("robot.look.front_strip.shade"));
}

}  // namespace
}  // namespace irloc::sim
