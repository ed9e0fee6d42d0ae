// irloc-sim with several wall cameras (issue 14): one dataset and one irlocd per camera, each with
// its own component ID; the combined stream hands the robot from camera to camera. A small
// two-camera drive end to end, the choice of the combined pose on hand-made poses, and the
// scenario's checks of the `cameras:` list.

#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "host_sim/metrics/camera_handover.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/run/simulation_run.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

using ::testing::HasSubstr;

const std::string kCalibration =
    "calibration:\n      image_width: 320\n      image_height: 240\n"
    "      camera_matrix: {rows: 3, cols: 3, data: [250, 0, 159.5, 0, 250, 119.5, 0, 0, 1]}\n"
    "      distortion_model: plumb_bob\n      distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";

// Two 320 x 240 cameras 2.4 m up on the south wall, 4 m apart, each pitched 45 degrees down and
// seeing about 2 m either side of itself at y = 2; the robot drives along y = 2 from out of both
// views (x -2) through camera 0's view, then camera 1's, and out again (x 7.8). 5 frames a second.
std::string two_cameras(const std::string& second_camera_extra = "", const std::string& extra = "") {
  return "kind: outside_in\nseed: 5\nframes: 64\ncameras:\n"
         "  - " + kCalibration +
         "    frame_rate: 5\n    wall: {position: [1.0, 0.0], height: 2.4, pitch_deg: 45, yaw_deg: 90}\n"
         "    floor_reference: [[0.0, 1.5], [0.0, 3.0], [2.0, 3.0], [2.0, 1.5]]\n"
         "  - " + kCalibration +
         "    frame_rate: 5\n    wall: {position: [5.0, 0.0], height: 2.4, pitch_deg: 45, yaw_deg: 90}\n"
         "    floor_reference: [[4.0, 1.5], [4.0, 3.0], [6.0, 3.0], [6.0, 1.5]]\n" + second_camera_extra +
         "robot:\n  body: {length: 0.60, width: 0.40, height: 0.35}\n"
         "trajectory:\n  type: waypoints\n  points: [[-2.0, 2.0], [7.8, 2.0]]\n  speed: 0.8\n"
         "metrics:\n  warm_up_frames: 10\n" + extra;
}

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(OutsideInCameras, TheCombinedStreamHandsTheRobotFromCameraToCamera) {
  test::TempDir dir;
  const Scenario scenario = parse_scenario(two_cameras(), "two.yaml");
  ASSERT_TRUE(scenario.outside_in);
  ASSERT_EQ(scenario.outside_in->cameras.size(), 2u);
  const RunOutputs outputs = run_scenario(scenario, dir.path());
  ASSERT_EQ(outputs.cameras.size(), 2u);
  ASSERT_TRUE(outputs.outside_in);
  const OutsideInMetrics& combined = *outputs.outside_in;
  for (const WallCameraRun& camera : outputs.cameras) {
    SCOPED_TRACE(camera.component_id);
    EXPECT_GT(camera.metrics.eligible_posed, 5);  // each camera poses the robot
    EXPECT_GE(camera.metrics.pose_rate, 0.8);
    EXPECT_LE(camera.metrics.position_rms, 0.030);
    EXPECT_EQ(camera.metrics.poses_off_robot, 0);
    EXPECT_LE(camera.metrics.poses_out_of_view, 1);  // as the box's corner crosses the image edge
    // Covered and posed more often together than by either camera alone.
    EXPECT_GT(combined.eligible, camera.metrics.eligible);
    EXPECT_GT(combined.eligible_posed, camera.metrics.eligible_posed);
  }
  EXPECT_EQ(outputs.cameras[0].component_id, 201);
  EXPECT_EQ(outputs.cameras[1].component_id, 202);
  EXPECT_GE(combined.pose_rate, 0.8);
  EXPECT_LE(combined.position_rms, 0.030);
  EXPECT_EQ(combined.poses_off_robot, 0);
  EXPECT_EQ(combined.heading_flips, 0);
  EXPECT_GE(outputs.hand_overs, 1);
  // Each irlocd ran with its own component ID and wrote its own pose CSV.
  EXPECT_THAT(file_text(dir.path() / "camera_1" / "dataset" / "config.yaml"), HasSubstr("--component-id 202"));
  EXPECT_EQ(read_pose_csv(dir.path() / "camera_0" / "pose.csv").size(), 64u);
  EXPECT_THAT(file_text(dir.path() / "outside_in_metrics.json"), HasSubstr("\"component_id\": 202"));
  for (const char* name : {"handover.png", "room.png", "metrics.json", "trajectory.png", "camera_0/outside_in_metrics.json",
                           "camera_1/errors.png"}) {
    EXPECT_GT(std::filesystem::file_size(dir.path() / name), 0u) << name;
  }
}

PoseEstimate ok_pose(std::uint64_t seq, double x, double y) {
  PoseEstimate pose;
  pose.seq = seq;
  pose.ok = true;
  pose.x = x;
  pose.y = y;
  pose.source = SourceKind::external;
  return pose;
}

TEST(OutsideInCameras, TheCombinedPoseIsTheNearerCamerasAndHandOversAreCounted) {
  WallCamera west, east;
  west.position = {0, 0};
  east.position = {10, 0};
  east.yaw_deg = 180;
  const auto truth_at = [](std::uint64_t seq, double x, bool whole, double hidden) {
    return OutsideInTruth{TruthRow{seq, 0, false, x, 0, 0, 0, 0, 0}, whole, hidden};
  };
  // West sees frames 0-2 (frame 2 half hidden), east frames 1-3; frame 4 neither.
  const std::vector<std::vector<OutsideInTruth>> truth = {
      {truth_at(0, 3, true, 0), truth_at(1, 5, true, 0), truth_at(2, 6, true, 0.5), truth_at(3, 7, false, 0), truth_at(4, 12, false, 0)},
      {truth_at(0, 3, false, 0), truth_at(1, 5, true, 0.1), truth_at(2, 6, true, 0.3), truth_at(3, 7, true, 0), truth_at(4, 12, false, 0)}};
  const std::vector<std::vector<PoseEstimate>> poses = {
      {ok_pose(0, 3.01, 0), ok_pose(1, 4.9, 0), ok_pose(2, 6.0, 0)},
      {ok_pose(1, 5.05, 0), ok_pose(2, 6.02, 0), ok_pose(3, 7.0, 0)}};
  const CameraHandOver combined = combine_cameras({west, east}, truth, poses);
  EXPECT_EQ(combined.camera, (std::vector<int>{0, 0, 1, 1, -1}));  // 4.9 m from west < 5.05 from east; 6.02 nearer east
  EXPECT_DOUBLE_EQ(combined.poses[1].x, 4.9);
  EXPECT_FALSE(combined.poses[4].ok);
  EXPECT_EQ(combined.hand_overs, 1);
  EXPECT_TRUE(combined.truth[0].whole_in_view);
  EXPECT_DOUBLE_EQ(combined.truth[2].hidden_fraction, 0.3);  // the clearer view counts
  EXPECT_FALSE(combined.truth[4].whole_in_view);
  EXPECT_LT(metres_per_pixel(west, {4.9, 0}), metres_per_pixel(east, {5.05, 0}));
}

TEST(OutsideInCameras, BadCameraListsAreRefusedNamingTheFileAndKey) {
  const auto message_of = [](const std::string& text) {
    return test::input_error_message([&] { parse_scenario(text, "rig.yaml"); });
  };
  std::string message = message_of(two_cameras("    component_id: 201\n"));
  EXPECT_THAT(message, HasSubstr("rig.yaml"));
  EXPECT_THAT(message, HasSubstr("cameras[1].component_id"));
  EXPECT_THAT(message, HasSubstr("another camera's"));

  std::string other_rate = two_cameras();
  other_rate.replace(other_rate.rfind("frame_rate: 5"), 13, "frame_rate: 10");
  message = message_of(other_rate);
  EXPECT_THAT(message, HasSubstr("cameras[1].frame_rate"));

  message = message_of(two_cameras("", "floor_reference: [[0.0, 1.5], [0.0, 3.0], [2.0, 3.0], [2.0, 1.5]]\n"));
  EXPECT_THAT(message, HasSubstr("rig.yaml"));
  EXPECT_THAT(message, HasSubstr("each camera has its own floor_reference"));

  std::string both = two_cameras();
  both.replace(both.find("cameras:"), 0, "camera:\n  " + kCalibration + "  wall: {position: [0, 0], height: 2.4, pitch_deg: 38}\n");
  EXPECT_THAT(message_of(both), HasSubstr("give exactly one of 'camera'"));

  std::string off_tile = two_cameras();
  off_tile.replace(off_tile.find("[6.0, 1.5]]"), 11, "[6.2, 1.5]]");
  message = message_of(off_tile);
  EXPECT_THAT(message, HasSubstr("cameras[1].floor_reference"));
  EXPECT_THAT(message, HasSubstr("corner 3 is not a tile corner"));
}

}  // namespace
}  // namespace irloc::sim
