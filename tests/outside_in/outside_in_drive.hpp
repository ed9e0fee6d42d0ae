#pragma once
// Drives an OutsideInSource through a rendered scenario and scores it against the truth.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "algo/kernels/blob_labeller.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/outside_in/outside_in_source.hpp"
#include "host_sim/render/floor_reference.hpp"
#include "host_sim/render/outside_in_renderer.hpp"

namespace irloc::test {

// The scene and its renderer live in host_sim/render/ (irloc-sim renders the same scenes).
using sim::FrameTruth;
using sim::Person;
using sim::SceneRenderer;
using sim::SceneState;
using sim::WallCamera;
using sim::WallProjection;

// The floor reference of the wall camera: a 2 m x 1 m rectangle of tile corners, its pixels
// measured to 0.1 px.
inline outside_in::FloorReference floor_reference_of(const WallCamera& camera) {
  return sim::measured_floor_reference(camera, {Eigen::Vector2d(2.5, 1.0), Eigen::Vector2d(4.5, 1.0),
                                                Eigen::Vector2d(4.5, -1.0), Eigen::Vector2d(2.5, -1.0)});
}

// A wall camera (the goal's by default) rendering the box alone, without noise or auto-exposure,
// and the box model the source fits.
struct CleanBoxView {
  WallCamera camera;
  SceneRenderer renderer{camera};
  CameraModel model{camera.intrinsics};
  outside_in::BoxSilhouette box{model, camera.world_from_camera().inverse(), outside_in::BoxBody{}};

  explicit CleanBoxView(const WallCamera& wall_camera = {}) : camera(wall_camera) {
    renderer.auto_exposure = false;
    renderer.noise_sigma = 0;
  }

  // The box's silhouette at pose, found as its dark pixels, opened (3 x 3) and closed (5 x 5) as
  // the source's mask is (the model's extent allows for the opening). Fails the test unless it
  // is one blob.
  void seen(const outside_in::FloorPose& pose, outside_in::Silhouette& silhouette) {
    SceneState scene;
    scene.robot = pose;
    FrameTruth truth;
    const auto& pixels = renderer.render(scene, truth);
    const int width = camera.intrinsics.width, height = camera.intrinsics.height;
    std::vector<std::uint8_t> dark(pixels.size()), scratch(pixels.size()), mask(pixels.size());
    for (std::size_t i = 0; i < dark.size(); ++i) dark[i] = pixels[i] < 80 ? 255 : 0;  // the dark box
    outside_in::OpenAndClose(width).apply(ImageView8(dark.data(), width, height), MutableImageView8(scratch.data(), width, height),
                              MutableImageView8(mask.data(), width, height));
    BlobLabeller labeller(100000);
    BlobList blobs;
    labeller.label(ImageView8(mask.data(), width, height), BlobParams{100}, blobs);
    ASSERT_EQ(blobs.size(), 1u);
    silhouette = outside_in::silhouette_of(blobs[0]);
  }
};

struct OutsideInRig {
  WallCamera camera;
  RigidTransform mount;  // unused by the outside-in source
  MarkerMap map;
  outside_in::OutsideInConfig config;
  std::unique_ptr<outside_in::OutsideInSource> source;

  explicit OutsideInRig(WallCamera wall_camera = {}) : camera(wall_camera) {
    config.floor_reference = floor_reference_of(camera);
    source = std::make_unique<outside_in::OutsideInSource>(SourceSetup{camera.intrinsics, mount, Dof::planar3, map}, config);
  }
};

struct ScenarioScore {
  int eligible = 0;         // robot whole in view, under 20 % hidden, after the warm-up
  int eligible_posed = 0;
  int poses_without_robot = 0;   // a pose while the robot is not whole in view
  int far_poses = 0;             // a pose more than 0.15 m from the robot (on a person, a ghost)
  int flips = 0;                 // a heading more than 90 degrees off
  double sum_position2 = 0, sum_heading2 = 0;
  double worst_heading = 0;      // rad, of the eligible poses
  int scored = 0;
  double position_rms() const { return std::sqrt(sum_position2 / std::max(scored, 1)); }
  double heading_rms_deg() const { return std::sqrt(sum_heading2 / std::max(scored, 1)) * 180 / std::numbers::pi; }
  double pose_rate() const { return eligible ? double(eligible_posed) / eligible : 0; }
};

// Prints a scenario's score under `label` and expects the goal's accuracy (position RMS <= 20 mm,
// heading RMS <= 2 degrees), no pose off the robot, flipped or without it, and at least
// `min_pose_rate` of the eligible frames posed.
inline void expect_scenario_goal(const ScenarioScore& score, const char* label, double min_pose_rate) {
  std::printf("%s: %d/%d eligible frames posed (%.1f %%), position RMS %.1f mm, heading RMS %.2f deg, far poses %d, "
              "flips %d, poses without robot %d\n",
              label, score.eligible_posed, score.eligible, 100 * score.pose_rate(), 1000 * score.position_rms(),
              score.heading_rms_deg(), score.far_poses, score.flips, score.poses_without_robot);
  EXPECT_GE(score.pose_rate(), min_pose_rate);
  EXPECT_LE(score.position_rms(), 0.020);
  EXPECT_LE(score.heading_rms_deg(), 2.0);
  EXPECT_EQ(score.far_poses, 0);
  EXPECT_EQ(score.flips, 0);
  EXPECT_EQ(score.poses_without_robot, 0);
}

// Renders frames 0..count-1 of scene_at(i), runs the source on each, scores poses from frame
// `warm_up` on.
inline ScenarioScore run_scenario(OutsideInRig& rig, SceneRenderer& renderer, int count, int warm_up,
                                  const std::function<SceneState(int)>& scene_at, double fps = 10) {
  ScenarioScore score;
  SourceResult result;
  for (int i = 0; i < count; ++i) {
    const SceneState scene = scene_at(i);
    FrameTruth truth;
    const auto& pixels = renderer.render(scene, truth);
    const Frame frame{static_cast<std::uint64_t>(i), static_cast<std::int64_t>(i * 1e9 / fps), false,
                      ImageView8(pixels.data(), rig.camera.intrinsics.width, rig.camera.intrinsics.height)};
    rig.source->process({frame, nullptr}, result);
    const bool visible = truth.robot_whole_in_view;
    const bool eligible = visible && truth.hidden_fraction() < 0.2 && i >= warm_up;
    score.eligible += eligible;
    if (!result.ok) continue;
    if (!visible) {
      ++score.poses_without_robot;
      continue;
    }
    const outside_in::FloorPose& robot = *scene.robot;
    const double error = std::hypot(result.world_from_base.translation.x() - robot.x,
                                    result.world_from_base.translation.y() - robot.y);
    const double yaw = std::atan2(result.world_from_base.rotation(1, 0), result.world_from_base.rotation(0, 0));
    const double heading_error = std::remainder(yaw - robot.yaw, 2 * std::numbers::pi);
    if (error > 0.15) ++score.far_poses;
    if (std::abs(heading_error) > std::numbers::pi / 2) ++score.flips;
    if (eligible) {
      ++score.eligible_posed;
      score.sum_position2 += error * error;
      score.sum_heading2 += heading_error * heading_error;
      score.worst_heading = std::max(score.worst_heading, std::abs(heading_error));
      ++score.scored;
    }
  }
  return score;
}

// The robot on an ellipse 2.0 - 6.0 m from the wall, driving forward at 0.5 m/s.
inline outside_in::FloorPose ellipse_pose(double t_s, double phase = 0) {
  constexpr double kCx = 4.0, kA = 2.0, kB = 0.7, kSpeed = 0.5;
  const double angle = phase + kSpeed * t_s / 1.5;  // rad; about 0.5 m/s on this ellipse
  const double x = kCx + kA * std::cos(angle), y = kB * std::sin(angle);
  return {x, y, std::atan2(kB * std::cos(angle), -kA * std::sin(angle))};
}

// Frame i of the goal scenario at 10 fps: the robot drives 2-6 m from the wall, a person walks
// through (in front of it for a while), the lamp goes down and up again, the sun patch drifts,
// auto-exposure follows.
inline SceneState goal_scene(int i) {
  SceneState scene;
  scene.robot = ellipse_pose(i / 10.0);
  if (i >= 30 && i < 80) scene.person = Person{Eigen::Vector2d(3.4 - 0.01 * (i - 30), 2.6 - 0.11 * (i - 30))};
  scene.lamp = (i >= 60 && i < 100) ? 0.7 : 1.0;
  scene.sun = Eigen::Vector2d(3.0 + 0.002 * i, 1.2);
  return scene;
}

}  // namespace irloc::test
