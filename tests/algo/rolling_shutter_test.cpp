// The rolling-shutter helpers (algo/source/rolling_shutter.hpp) on exact synthetic motion: the
// arc through two poses is the motion that drew it; a point moved to the frame's time projects from
// the pose at t_ns where the real point projects from the pose at its row's time; a pixel moved to
// the frame's time is where the pose at t_ns sees the point; unknown motion inflates only the
// free parameters.

#include <algorithm>
#include <cmath>
#include <optional>

#include <gtest/gtest.h>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/source/rolling_shutter.hpp"
#include "tests/algo/board_camera.hpp"

namespace irloc {
namespace {

RigidTransform level_pose(double x, double y, double yaw) {
  return {rotation_from_rpy(0, 0, yaw), Eigen::Vector3d(x, y, 0)};
}

using test::board_camera;
using test::up_mount;

TEST(RollingShutter, TheArcThroughTwoPosesIsTheMotionThatDrewIt) {
  const RigidTransform start = level_pose(0.4, -0.2, 2.9);
  for (const FrameMotion& motion : {FrameMotion{{1.0, 0, 0}, 1.5708}, FrameMotion{{0.6, -0.2, 0}, -1.2},
                                   FrameMotion{{0.8, 0, 0}, 0.0}, FrameMotion{{0, 0, 0}, 1.5}}) {
    const RigidTransform end = pose_after(start, 0.05, motion);
    const PosePrior prior{start, 1'000'000'000};
    const std::optional<FrameMotion> found = motion_since(&prior, end, 1'050'000'000, kMaxTrackGapNs);
    ASSERT_TRUE(found.has_value());
    EXPECT_LT((found->velocity - motion.velocity).norm(), 1e-9);
    EXPECT_NEAR(found->yaw_rate, motion.yaw_rate, 1e-9);
    // A robot on an arc: its speed along the path is the body velocity's norm.
    EXPECT_NEAR((pose_after(start, 0.001, motion).translation - start.translation).norm(), 0.001 * motion.velocity.norm(), 1e-6);
  }
  const PosePrior old{start, 0};
  EXPECT_FALSE(motion_since(&old, start, kMaxTrackGapNs + 1, kMaxTrackGapNs).has_value());
  EXPECT_FALSE(motion_since(nullptr, start, 1, kMaxTrackGapNs).has_value());
}

TEST(RollingShutter, APoseBeyondTheFastestRobotsReachRefusesTheTrack) {
  const RigidTransform start = level_pose(0.4, -0.2, 3.1);
  const PosePrior prior{start, 1'000'000'000};
  const std::int64_t t_ns = 1'050'000'000;  // 50 ms on: the fastest robot's reach is 50 mm and 4.5 deg
  const MotionLimits fastest;                // the config's default: 1 m/s, 90 deg/s
  // The fastest robot's own drives (straight, turning on the spot, both; across the yaw wrap) are
  // within reach ...
  for (const FrameMotion& motion : {FrameMotion{{fastest.speed, 0, 0}, 0.0}, FrameMotion{{0, 0, 0}, fastest.yaw_rate},
                                   FrameMotion{{0, fastest.speed, 0}, -fastest.yaw_rate}}) {
    EXPECT_FALSE(beyond_reach(prior, pose_after(start, 0.05, motion), t_ns, fastest));
  }
  // ... a pose carried 0.5 m or turned 20 degrees is not.
  EXPECT_TRUE(beyond_reach(prior, level_pose(0.9, -0.2, 3.1), t_ns, fastest));
  EXPECT_TRUE(beyond_reach(prior, level_pose(0.4, -0.2, 3.1 + 0.35), t_ns, fastest));
  EXPECT_TRUE(beyond_reach(prior, level_pose(0.4, -0.2, 3.1 - 0.35), t_ns, fastest));
}

TEST(RollingShutter, TheReachIsTheConfiguredRobots) {
  const RigidTransform start = level_pose(0.4, -0.2, 3.1);
  const PosePrior prior{start, 1'000'000'000};
  const std::int64_t t_ns = 1'050'000'000;
  // 2.5 m/s and 270 deg/s for 50 ms: beyond the default robot's reach, within a robot's configured so.
  const RigidTransform moved = pose_after(start, 0.05, FrameMotion{{2.5, 0, 0}, 4.7});
  EXPECT_TRUE(beyond_reach(prior, moved, t_ns, MotionLimits{}));
  EXPECT_FALSE(beyond_reach(prior, moved, t_ns, MotionLimits{2.5, 4.8}));
  // ... and a slower robot's reach is shorter.
  EXPECT_TRUE(beyond_reach(prior, pose_after(start, 0.05, FrameMotion{{0.5, 0, 0}, 0}), t_ns, MotionLimits{0.2, 0.5}));
}

TEST(RollingShutter, TheMotionBeforeAGapIsAPriorThatGrowsWithTheGap) {
  const MotionLimits fastest;  // 1 m/s, 90 deg/s
  const FrameMotion before{{0.8, 0.05, 0.01}, -1.1};
  // 200 ms: the velocity may have changed by 1 m/s * 90 deg/s * 0.2 s, the yaw rate by (90 deg/s)^2 * 0.2 s,
  // on top of the track's own uncertainty; the mean is the track's motion, without climb.
  const std::optional<MotionPrior> prior = motion_prior_after_gap(before, 0.01 * 0.01, 0.02 * 0.02, 0.2, fastest);
  ASSERT_TRUE(prior.has_value());
  EXPECT_NEAR(prior->velocity_sigma, std::hypot(0.01, 0.2 * fastest.yaw_rate * fastest.speed), 1e-12);
  EXPECT_NEAR(prior->yaw_rate_sigma, std::hypot(0.02, 0.2 * fastest.yaw_rate * fastest.yaw_rate), 1e-12);
  EXPECT_EQ(prior->mean.velocity, Eigen::Vector3d(0.8, 0.05, 0));
  EXPECT_EQ(prior->mean.yaw_rate, -1.1);
  // A slower-turning robot's motion changes more slowly.
  EXPECT_LT(motion_prior_after_gap(before, 0, 0, 0.2, MotionLimits{1.0, 0.5})->velocity_sigma, prior->velocity_sigma);
  // Past 1 / max_yaw_rate (0.64 s) the prior is no narrower than the fastest robot's: none.
  EXPECT_TRUE(motion_prior_after_gap(before, 0, 0, 0.6, fastest).has_value());
  EXPECT_FALSE(motion_prior_after_gap(before, 0, 0, 0.65, fastest).has_value());
}

TEST(RollingShutter, MovedPointsAndPixelsAreWhatThePoseAtTheFrameTimeSees) {
  const CameraModel camera(board_camera());
  const RigidTransform mount = up_mount();
  const RigidTransform at_t = level_pose(1.0, 2.0, 0.7);
  const FrameMotion motion{{1.0, 0.1, 0}, 1.5708};
  const Eigen::Vector3d world(1.3, 1.6, 2.6);
  const double dt = 0.02;  // the row 529 of the board's camera
  const RigidTransform camera_then = (pose_after(at_t, dt, motion) * mount).inverse();
  const RigidTransform camera_now = (at_t * mount).inverse();
  Eigen::Vector2d seen_then, seen_now, moved_seen_now;
  ASSERT_TRUE(camera.project(camera_then * world, seen_then));
  ASSERT_TRUE(camera.project(camera_now * world, seen_now));
  EXPECT_GT((seen_then - seen_now).norm(), 5.0);  // the motion within the frame shows

  const Eigen::Vector3d moved = point_seen_at_frame_time(world, dt, motion, at_t);
  ASSERT_TRUE(camera.project(camera_now * moved, moved_seen_now));
  EXPECT_LT((moved_seen_now - seen_then).norm(), 1e-9);

  const Eigen::Vector2d back = pixel_at_frame_time(seen_then, dt, motion, at_t, mount, camera, world.z());
  EXPECT_LT((back - seen_now).norm(), 1e-6);
}

// The bound on how far a point moved to t_ns goes when moved with a pose a little off holds at
// every row time and offset tried, and is loose by at most about 3x (the position and yaw terms
// are added, whatever their directions).
TEST(RollingShutter, MovedPointChangeBoundsTheMoveOfAnotherPose) {
  const RigidTransform at_t = level_pose(1.0, 2.0, 0.7);
  const FrameMotion motion{{0.9, 0.2, 0}, -1.5};
  const Eigen::Vector3d world(1.3, 1.6, 2.6);
  const double max_dt = 0.0233;  // the board's camera's readout
  for (const RigidTransform& off : {level_pose(1.0005, 2.0, 0.7), level_pose(1.0, 1.998, 0.7), level_pose(1.0, 2.0, 0.701),
                                    level_pose(0.999, 2.001, 0.699)}) {
    const double bound = moved_point_change(at_t, off, motion, max_dt);
    EXPECT_GT(bound, 0);
    double largest = 0;
    for (double dt = 0; dt <= max_dt; dt += max_dt / 8) {
      largest = std::max(largest, (point_seen_at_frame_time(world, dt, motion, at_t) -
                                   point_seen_at_frame_time(world, dt, motion, off)).norm());
    }
    EXPECT_LE(largest, bound * 1.01);
    EXPECT_GT(largest, bound * 0.3);
  }
  EXPECT_EQ(moved_point_change(at_t, at_t, motion, max_dt), 0);
}

TEST(RollingShutter, UnknownMotionInflatesOnlyTheFreeParameters) {
  PoseCovariance covariance = PoseCovariance::Zero();
  covariance(0, 0) = covariance(1, 1) = 1e-8;
  covariance(5, 5) = 1e-8;  // dof 3: x, y, yaw
  const MotionLimits fastest{1.5, 2.0};
  add_unknown_motion(0.0116, fastest, covariance);  // the board's middle row
  EXPECT_NEAR(std::sqrt(covariance(0, 0)), fastest.speed * 0.0116, 1e-5);
  EXPECT_NEAR(std::sqrt(covariance(5, 5)), fastest.yaw_rate * 0.0116, 1e-5);
  EXPECT_EQ(covariance(2, 2), 0);
  EXPECT_EQ(covariance(3, 3), 0);
}

}  // namespace
}  // namespace irloc
