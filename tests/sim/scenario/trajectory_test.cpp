// Trajectories: loops, waypoints with turns, lawn-mower sweeps and spins move as specified.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "host_sim/scenario/trajectory.hpp"

namespace irloc::sim {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Trajectory, LoopStaysOnItsCircleFacingAlongIt) {
  TrajectorySpec spec;
  spec.kind = TrajectoryKind::loop;
  spec.centre = {1, -2};
  spec.radius = 0.8;
  spec.speed = 0.4;
  const Trajectory trajectory(spec);
  EXPECT_NEAR(trajectory.duration(), 2 * kPi * 0.8 / 0.4, 1e-12);
  for (double t = 0; t < 15; t += 0.7) {
    const PlanarPose pose = trajectory.pose_at(t);
    EXPECT_NEAR(std::hypot(pose.x - 1, pose.y + 2), 0.8, 1e-12);
    // Moving a little further goes along the heading.
    const PlanarPose next = trajectory.pose_at(t + 1e-5);
    EXPECT_NEAR(std::atan2(next.y - pose.y, next.x - pose.x), pose.yaw, 1e-4);
  }
}

TEST(Trajectory, WaypointsDriveAtTheirSpeedsAndTurnInPlace) {
  TrajectorySpec spec;
  spec.kind = TrajectoryKind::waypoints;
  spec.points = {{0, 0}, {2, 0}, {2, 1}};
  spec.speeds = {1.0, 0.5};
  spec.turn_rate = kPi / 2;  // the 90 degree corner takes 1 s
  const Trajectory trajectory(spec);
  EXPECT_NEAR(trajectory.duration(), 2 + 1 + 2, 1e-12);
  PlanarPose pose = trajectory.pose_at(1.0);
  EXPECT_NEAR(pose.x, 1, 1e-12);
  EXPECT_NEAR(pose.yaw, 0, 1e-12);
  pose = trajectory.pose_at(2.5);  // half way through the turn, standing at the corner
  EXPECT_NEAR(pose.x, 2, 1e-12);
  EXPECT_NEAR(pose.y, 0, 1e-12);
  EXPECT_NEAR(pose.yaw, kPi / 4, 1e-12);
  pose = trajectory.pose_at(4.0);
  EXPECT_NEAR(pose.y, 0.5, 1e-12);
  EXPECT_NEAR(pose.yaw, kPi / 2, 1e-12);
  pose = trajectory.pose_at(100);  // an open path holds its end
  EXPECT_NEAR(pose.x, 2, 1e-12);
  EXPECT_NEAR(pose.y, 1, 1e-12);
}

TEST(Trajectory, LawnMowerSweepsEveryLane) {
  TrajectorySpec spec;
  spec.kind = TrajectoryKind::lawn_mower;
  spec.area = {0, 0, 2, 1};
  spec.spacing = 0.5;
  spec.speed = 1;
  const Trajectory trajectory(spec);
  bool lane_seen[3] = {false, false, false};
  for (double t = 0; t < trajectory.duration(); t += 0.01) {
    const PlanarPose pose = trajectory.pose_at(t);
    EXPECT_GE(pose.x, -1e-9);
    EXPECT_LE(pose.x, 2 + 1e-9);
    for (int lane = 0; lane < 3; ++lane) {
      if (std::abs(pose.y - 0.5 * lane) < 1e-9 && std::abs(pose.x - 1) < 0.01) lane_seen[lane] = true;
    }
  }
  EXPECT_TRUE(lane_seen[0] && lane_seen[1] && lane_seen[2]);
}

TEST(Trajectory, SpinTurnsInPlace) {
  TrajectorySpec spec;
  spec.kind = TrajectoryKind::spin;
  spec.pose = {0.5, 0.25, 0.1};
  spec.rate = 0.5;
  const Trajectory trajectory(spec);
  const PlanarPose pose = trajectory.pose_at(2);
  EXPECT_EQ(pose.x, 0.5);
  EXPECT_EQ(pose.y, 0.25);
  EXPECT_NEAR(pose.yaw, 1.1, 1e-12);
}

}  // namespace
}  // namespace irloc::sim
