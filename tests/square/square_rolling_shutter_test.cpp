// The square path under a rolling shutter: a ray-cast fisheye whose row v is seen v * line_time
// after the frame's t_ns from a robot driving and turning (the pose per row in closed form,
// tests/square/tape_scene.hpp). With the motion within the frame, the detector moves the tape
// points to t_ns before it fits the sides (TapePoints::collect) and finds the robot's pose at
// t_ns as closely as from a global shutter's frame of that pose; without it, millimetres off.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "algo/markers/square/square_detector.hpp"
#include "algo/pipeline/localizer.hpp"
#include "algo/source/rolling_shutter.hpp"
#include "tests/square/tape_scene.hpp"
#include "tests/square/tape_scene_localizer.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

constexpr double kDegree = std::numbers::pi / 180;

struct PoseError {
  double position = 0;  // m
  double yaw = 0;       // rad
};

PoseError error_of(const SquareDetection& detection, const TapeScene& scene) {
  const RigidTransform& pose = detection.world_from_base;
  return {std::hypot(pose.translation.x() - scene.x, pose.translation.y() - scene.y),
          std::abs(wrap_angle(std::atan2(pose.rotation(1, 0), pose.rotation(0, 0)) - scene.yaw))};
}

SquareDetection detect(SquareDetector& detector, const Image8& on_frame, const Image8& off_frame, const RowMotion* rows) {
  const ImageView8 on(on_frame.view()), off(off_frame.view());
  return detector.detect(on, off, shared_noise(on, off), nullptr, rows);
}

TEST(SquareRollingShutter, TapePointsMovedToTheFrameTimeGiveThePoseThere) {
  // The eval's fisheye at half its resolution, its rows read in the same 18.4 ms; 0.8 m/s and
  // 60 deg/s (square_rolling_fisheye.yaml).
  TapeScene global;
  global.camera = fisheye(640, 512);
  global.samples = 2;
  SquareDetector detector(global.camera, 8, to_rigid(global.mount), Dof::planar3, global.marker, SquareConfig{});
  const FrameMotion motion{Eigen::Vector3d(0.8, 0, 0), 60 * kDegree};
  const RowMotion rows{motion, 36e-6};
  // A robot turning left at (0.3, -0.2) headed 40 degrees: each side of the square is seen over
  // hundreds of rows.
  global.x = 0.3;
  global.y = -0.2;
  global.yaw = 0.7;
  TapeScene rolling = global;
  rolling.line_time = rows.line_time;
  rolling.velocity = motion.velocity.head<2>();
  rolling.yaw_rate = motion.yaw_rate;
  Image8 global_on, global_off, rolling_on, rolling_off;
  global.render(global_on, global_off);
  rolling.render(rolling_on, rolling_off);

  const SquareDetection from_global = detect(detector, global_on, global_off, nullptr);
  const SquareDetection moved = detect(detector, rolling_on, rolling_off, &rows);
  const SquareDetection as_seen = detect(detector, rolling_on, rolling_off, nullptr);
  ASSERT_TRUE(from_global.found()) << to_string(from_global.outcome);
  ASSERT_TRUE(moved.found()) << to_string(moved.outcome);
  ASSERT_TRUE(as_seen.found()) << to_string(as_seen.outcome);
  const PoseError global_error = error_of(from_global, global);
  const PoseError moved_error = error_of(moved, rolling);
  const PoseError seen_error = error_of(as_seen, rolling);
  std::printf("global %.2f mm %.3f deg, moved %.2f mm %.3f deg, as seen %.2f mm %.3f deg\n", 1e3 * global_error.position,
              global_error.yaw / kDegree, 1e3 * moved_error.position, moved_error.yaw / kDegree,
              1e3 * seen_error.position, seen_error.yaw / kDegree);
  EXPECT_LT(moved_error.position, global_error.position + 0.001);
  EXPECT_LT(moved_error.yaw, global_error.yaw + 0.05 * kDegree);
  // What the motion does to the pose as seen.
  EXPECT_GT(seen_error.position, 0.004);
  EXPECT_GT(seen_error.yaw, 0.3 * kDegree);
}

// A drive's frame: where and how the robot drives, rendered by the eval's fisheye at half its
// resolution (rows read in 18.4 ms), with and without the rolling shutter.
struct Drive {
  double x, y, yaw;
  FrameMotion motion;
};
// Two drives: turning left while driving ahead, and turning right while drifting sideways, at
// other places under the square.
const Drive kDrives[] = {{0.3, -0.2, 0.7, {Eigen::Vector3d(0.8, 0, 0), 60 * kDegree}},
                         {-0.25, 0.3, -2.0, {Eigen::Vector3d(0.6, -0.4, 0), -85 * kDegree}}};
constexpr double kLineTime = 72e-6;

struct DriveFrames {
  TapeScene global, rolling;
  Image8 global_on, global_off, rolling_on, rolling_off;
};

void render_drive(const Drive& drive, DriveFrames& frames) {
  frames.global.camera = fisheye(640, 512);
  frames.global.samples = 2;
  frames.global.x = drive.x;
  frames.global.y = drive.y;
  frames.global.yaw = drive.yaw;
  frames.rolling = frames.global;
  frames.rolling.line_time = kLineTime;
  frames.rolling.velocity = drive.motion.velocity.head<2>();
  frames.rolling.yaw_rate = drive.motion.yaw_rate;
  frames.global.render(frames.global_on, frames.global_off);
  frames.rolling.render(frames.rolling_on, frames.rolling_off);
}

// The detector of the drives' camera.
SquareDetector drive_detector() {
  const TapeScene scene;
  return SquareDetector(fisheye(640, 512), 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
}

// How far `moved` lies from the scene's pose in sigmas of the motion fit's x-y covariance.
double sigmas_off(const SquareDetection& moved, const TapeMotionFit& fit, const TapeScene& scene) {
  const Eigen::Matrix2d xy = fit.pose_covariance.topLeftCorner<2, 2>();
  const Eigen::Vector2d miss = moved.world_from_base.translation.head<2>() - Eigen::Vector2d(scene.x, scene.y);
  return std::sqrt(miss.dot(xy.inverse() * miss));
}

TEST(SquareRollingShutter, WithoutATrackTheFramesOwnTapeGivesTheMotionAndThePoseAtTheFrameTime) {
  // A drive's first frame: no motion known.
  SquareDetector detector = drive_detector();
  for (const Drive& drive : kDrives) {
    DriveFrames frames;
    render_drive(drive, frames);
    const TapeScene& global = frames.global;
    const TapeScene& rolling = frames.rolling;
    const Image8 &global_on = frames.global_on, &global_off = frames.global_off;
    const Image8 &rolling_on = frames.rolling_on, &rolling_off = frames.rolling_off;

    const SquareDetection from_global = detect(detector, global_on, global_off, nullptr);
    ASSERT_TRUE(from_global.found()) << to_string(from_global.outcome);
    const SquareDetection as_seen = detect(detector, rolling_on, rolling_off, nullptr);
    ASSERT_TRUE(as_seen.found()) << to_string(as_seen.outcome);
    const TapeMotionFit own = detector.fit_motion(as_seen, kLineTime, std::nullopt);
    ASSERT_TRUE(own.ok);
    const RowMotion rows{own.motion, kLineTime};
    const SquareDetection moved = detect(detector, rolling_on, rolling_off, &rows);
    ASSERT_TRUE(moved.found()) << to_string(moved.outcome);
    const PoseError global_error = error_of(from_global, global);
    const PoseError moved_error = error_of(moved, rolling);
    SquareDetection fitted;
    fitted.world_from_base = own.world_from_base;
    const PoseError fitted_error = error_of(fitted, rolling);
    const PoseError seen_error = error_of(as_seen, rolling);
    std::printf("motion (%.3f, %.3f) m/s %.1f deg/s (sigmas %.4f m/s, %.4f rad/s, %zu stretches); global %.2f mm, "
                "moved %.2f mm %.3f deg, fitted %.2f mm, as seen %.2f mm\n",
                own.motion.velocity.x(), own.motion.velocity.y(), own.motion.yaw_rate / kDegree, own.velocity_sigma,
                own.yaw_rate_sigma, own.stretches, 1e3 * global_error.position, 1e3 * moved_error.position,
                moved_error.yaw / kDegree, 1e3 * fitted_error.position, 1e3 * seen_error.position);
    // The motion, from the frame alone, within 3 sigma of the truth; the sigmas well inside the
    // fastest robot's bounds (what the source requires to use it).
    EXPECT_LT((own.motion.velocity - drive.motion.velocity).norm(), 3 * own.velocity_sigma);
    EXPECT_NEAR(own.motion.yaw_rate, drive.motion.yaw_rate, 3 * own.yaw_rate_sigma);
    EXPECT_LT(own.velocity_sigma, MotionLimits{}.speed / 4);
    EXPECT_LT(own.yaw_rate_sigma, MotionLimits{}.yaw_rate / 4);
    // The pose at t_ns: within 3 sigma (of x and y together) of the fit's own covariance, and far
    // closer than the plain fit, which is millimetres off.
    EXPECT_LT(sigmas_off(moved, own, rolling), 3.0);
    EXPECT_LT(moved_error.position, seen_error.position / 3);
    EXPECT_LT(moved_error.yaw, 3 * std::sqrt(own.pose_covariance(2, 2)) + global_error.yaw);
    EXPECT_GT(seen_error.position, 0.004);
  }
}

TEST(SquareRollingShutter, APriorOnTheMotionIsTakenWithTheFramesOwnTape) {
  // After a gap the track did not bridge, the motion before it is the prior of the tape's motion
  // fit (SourceInput::motion_prior), a MAP estimate. Here a prior at the drive's motion and far
  // narrower than the tape's own 0.06-0.08 m/s and rad/s, so that what it does shows: the fit
  // keeps the motion near the prior's mean where the tape alone is up to 0.13 m/s off. (After the
  // shortest gap the track does not bridge, 150 ms, motion_prior_after_gap's are 0.24 m/s and
  // 0.38 rad/s and wider: the tape then decides the motion nearly alone.)
  SquareDetector detector = drive_detector();
  for (const Drive& drive : kDrives) {
    DriveFrames frames;
    render_drive(drive, frames);
    const SquareDetection as_seen = detect(detector, frames.rolling_on, frames.rolling_off, nullptr);
    ASSERT_TRUE(as_seen.found()) << to_string(as_seen.outcome);
    const std::optional<MotionPrior> prior = MotionPrior{drive.motion, 0.01, 0.01, 0.01};
    const TapeMotionFit own = detector.fit_motion(as_seen, kLineTime, std::nullopt);
    const TapeMotionFit with_prior = detector.fit_motion(as_seen, kLineTime, prior);
    ASSERT_TRUE(own.ok);
    ASSERT_TRUE(with_prior.ok);
    const RowMotion rows{with_prior.motion, kLineTime};
    const SquareDetection moved = detect(detector, frames.rolling_on, frames.rolling_off, &rows);
    ASSERT_TRUE(moved.found()) << to_string(moved.outcome);
    const double own_velocity_error = (own.motion.velocity - drive.motion.velocity).norm();
    const double velocity_error = (with_prior.motion.velocity - drive.motion.velocity).norm();
    const double pose_error = error_of(moved, frames.rolling).position;
    std::printf("own: sigmas %.3f m/s %.3f rad/s, velocity %.3f m/s off; with the prior: sigmas %.3f m/s %.3f "
                "rad/s, velocity %.3f m/s off, yaw rate %.3f rad/s off, pose %.2f mm off\n",
                own.velocity_sigma, own.yaw_rate_sigma, own_velocity_error, with_prior.velocity_sigma,
                with_prior.yaw_rate_sigma, velocity_error, std::abs(with_prior.motion.yaw_rate - drive.motion.yaw_rate),
                1e3 * pose_error);
    EXPECT_LT(with_prior.velocity_sigma, prior->velocity_sigma);
    EXPECT_LT(with_prior.yaw_rate_sigma, prior->yaw_rate_sigma);
    EXPECT_LT(velocity_error, 0.03);
    EXPECT_NEAR(with_prior.motion.yaw_rate, drive.motion.yaw_rate, 0.03);
    EXPECT_LT(pose_error, 0.001);
    // The pose at t_ns within 3 sigma of the fit's own covariance.
    EXPECT_LT(sigmas_off(moved, with_prior, frames.rolling), 3.0);
  }
}

// A drive's first frame through the Localizer (no track): the square source fits the motion with
// the pose to the tape, the fastest robot the config describes as the motion's prior
// (frame_motion_prior). The tape decides the sideways speed least well (0.1-0.2 m/s); a robot
// that does not drive sideways (robot.max_side_speed 0.05 m/s: on wheels, its base origin on
// their axle) bounds it. On drives that do not slide, the first poses are then closer to the pose
// at t_ns than for a robot that may drive any way, and within their (narrower) covariance.
TEST(SquareRollingShutter, ARobotThatDoesNotDriveSidewaysGivesFirstPosesCloserToTheFrameTime) {
  struct Arc {
    double x, y, yaw, speed, yaw_rate;
    unsigned seed;
  };
  const Arc arcs[] = {{0.3, -0.2, 0.7, 0.8, 60 * kDegree, 3},   {-0.25, 0.3, -2.0, 0.6, -50 * kDegree, 4},
                      {0.1, 0.25, 2.6, 0.7, 45 * kDegree, 5},   {-0.2, -0.15, -0.6, 0.5, -60 * kDegree, 6},
                      {0.25, 0.1, 1.6, 0.8, -55 * kDegree, 7},  {-0.1, -0.3, -2.9, 0.4, 40 * kDegree, 8},
                      {0.0, 0.2, 0.2, 0.6, 35 * kDegree, 9},    {0.3, 0.3, -1.2, 0.7, -45 * kDegree, 10}};
  double squared = 0, squared_any_way = 0, squared_normalized = 0;
  for (const Arc& arc : arcs) {
    TapeScene scene;
    scene.camera = fisheye(640, 512);
    scene.samples = 2;
    scene.seed = arc.seed;
    scene.x = arc.x;
    scene.y = arc.y;
    scene.yaw = arc.yaw;
    scene.line_time = kLineTime;
    scene.velocity = Eigen::Vector2d(arc.speed, 0);
    scene.yaw_rate = arc.yaw_rate;
    Image8 on, off;
    scene.render(on, off);
    const auto first_pose = [&](std::optional<double> side_speed) {
      LocalizerSetup setup = setup_for(scene);
      setup.line_time_ns = std::llround(kLineTime * 1e9);
      setup.robot_limits.side_speed = side_speed;
      return Localizer(setup).process(pair_of(on, off));
    };
    const PoseEstimate pose = first_pose(0.05), any_way = first_pose(std::nullopt);
    ASSERT_TRUE(pose.ok);
    ASSERT_TRUE(any_way.ok);
    const Eigen::Vector2d miss(pose.x - arc.x, pose.y - arc.y);
    const double error = miss.norm(), error_any_way = std::hypot(any_way.x - arc.x, any_way.y - arc.y);
    const double sigmas = std::sqrt(miss.dot(pose.covariance.topLeftCorner<2, 2>().inverse() * miss));
    std::printf("first pose %.2f mm off (%.2f sigma); a robot that may drive any way: %.2f mm\n", 1e3 * error, sigmas,
                1e3 * error_any_way);
    EXPECT_LT(sigmas, 3.0);
    squared += error * error;
    squared_any_way += error_any_way * error_any_way;
    squared_normalized += sigmas * sigmas;
  }
  const double count = std::size(arcs);
  const double rms = std::sqrt(squared / count), rms_any_way = std::sqrt(squared_any_way / count);
  std::printf("first poses, RMS over %zu drives: %.2f mm (%.2f sigma); a robot that may drive any way %.2f mm\n",
              std::size(arcs), 1e3 * rms, std::sqrt(squared_normalized / count), 1e3 * rms_any_way);
  EXPECT_LT(rms, 0.8 * rms_any_way);
  EXPECT_LT(std::sqrt(squared_normalized / count), 1.5);
}

}  // namespace
}  // namespace irloc::test
