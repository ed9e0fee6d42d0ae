// The joint fit of the pose at t_ns and the motion within the frame (algo/source/pose_motion_fit.hpp)
// on exact synthetic rolling-shutter views of the default board's camera (820x616, 37.8 us a row):
// each dot's pixel is where the camera at its own row's time sees it (solved row by row, as the
// renderer draws it). Markers at different rows give back the pose and the motion; one marker
// spanning a few dozen rows leaves the motion unknown, and its standard deviations say so; with
// the fastest robot as the motion's prior, it gives what it shows of the motion.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/source/pose_motion_fit.hpp"
#include "algo/source/rolling_shutter.hpp"
#include "tests/algo/board_camera.hpp"

namespace irloc {
namespace {

constexpr std::int64_t kLineTimeNs = 37'800;

using test::board_camera;
using test::up_mount;

struct View {
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  std::vector<double> row_times;
};

// Dots in 3x3 grids of 8 cm round each centre on the ceiling 2.6 m up, seen under a rolling
// shutter: the pixel where the camera at the row's time sees the dot (the row found by iterating).
View rolling_view(const std::vector<Eigen::Vector2d>& centres, const RigidTransform& at_t_ns, const FrameMotion& motion) {
  const CameraModel camera(board_camera());
  View view;
  for (const Eigen::Vector2d& centre : centres) {
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        const Eigen::Vector3d dot(centre.x() + 0.08 * i, centre.y() + 0.08 * j, 2.6);
        Eigen::Vector2d pixel(0, 0);
        for (int pass = 0; pass < 20; ++pass) {
          const RigidTransform world_from_camera = pose_after(at_t_ns, row_time(pixel, kLineTimeNs), motion) * up_mount();
          EXPECT_TRUE(camera.project(world_from_camera.inverse() * dot, pixel));
        }
        view.world.push_back(dot);
        view.pixels.push_back(pixel);
        view.row_times.push_back(row_time(pixel, kLineTimeNs));
      }
    }
  }
  return view;
}

PoseMotionFit fit(const View& view, const RigidTransform& initial) {
  return fit_pose_and_motion(view.world, view.pixels, view.row_times, CameraModel(board_camera()), up_mount(), initial,
                             Dof::planar3, 0.05, std::nullopt);
}

// The exact view with its dots' pixels 0.15 px noisy, draw `seed`.
View noisy(const View& exact, unsigned seed) {
  View view = exact;
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0, 0.15);
  for (Eigen::Vector2d& pixel : view.pixels) pixel += Eigen::Vector2d(noise(random), noise(random));
  return view;
}

// Position errors over noise draws: a reference fit's, the MAP fit's, and the MAP fit's over the
// sigma its motion adds to the pose.
struct DrawErrors {
  double reference_square_sum = 0, square_sum = 0, normalized_square_sum = 0;
  int draws = 0;

  void add(const RigidTransform& reference, const PoseMotionFit& found, const RigidTransform& truth) {
    const double reference_error = (reference.translation - truth.translation).norm();
    const double error = (found.world_from_base.translation - truth.translation).norm();
    const PoseCovariance& added = found.motion_pose_covariance;
    reference_square_sum += reference_error * reference_error;
    square_sum += error * error;
    normalized_square_sum += error * error / (added(0, 0) + added(1, 1));
    ++draws;
  }
  double reference_rms() const { return std::sqrt(reference_square_sum / draws); }
  double rms() const { return std::sqrt(square_sum / draws); }
  double normalized_rms() const { return std::sqrt(normalized_square_sum / draws); }
};

TEST(PoseMotionFit, MarkersAtDifferentRowsGiveThePoseAndTheMotion) {
  const RigidTransform truth{rotation_from_rpy(0, 0, 0.7), Eigen::Vector3d(0.3, -0.2, 0)};
  const FrameMotion motion{{0.9, 0.1, 0}, 1.4};
  // Three markers seen at the top, the middle and the bottom of the image (the image's top
  // toward the robot's front, at heading 0.7).
  const Eigen::Matrix2d heading = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  const Eigen::Vector2d robot(0.35, -0.2);
  const View view = rolling_view({robot + heading * Eigen::Vector2d(0.7, 0.5), robot + heading * Eigen::Vector2d(0.05, -0.3),
                                  robot + heading * Eigen::Vector2d(-0.7, 0.4)},
                                 truth, motion);
  // From a pose 2 cm and 1.5 degrees off and no motion, as a plain fit would give.
  const RigidTransform initial{rotation_from_rpy(0, 0, 0.7 + 0.026), Eigen::Vector3d(0.315, -0.187, 0)};
  const PoseMotionFit found = fit(view, initial);
  ASSERT_TRUE(found.ok);
  EXPECT_LT((found.world_from_base.translation - truth.translation).norm(), 1e-5);
  EXPECT_NEAR(rpy_from_rotation(found.world_from_base.rotation).yaw, 0.7, 1e-5);
  EXPECT_LT((found.motion.velocity - motion.velocity).norm(), 1e-3);
  EXPECT_NEAR(found.motion.yaw_rate, motion.yaw_rate, 1e-3);
  EXPECT_LT(found.velocity_sigma, 0.05);
  EXPECT_LT(found.yaw_rate_sigma, 0.05);
  // What the motion's uncertainty adds to the pose's: a covariance of x, y and yaw only (dof 3).
  const PoseCovariance& added = found.motion_pose_covariance;
  EXPECT_GT(added(0, 0), 0);
  EXPECT_GT(added(5, 5), 0);
  EXPECT_EQ(added(2, 2), 0);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<PoseCovariance>(added).eigenvalues().minCoeff(), -1e-18);
}

TEST(PoseMotionFit, OneMarkerLeavesTheMotionUnknownAndSaysSo) {
  const RigidTransform truth{rotation_from_rpy(0, 0, -1.1), Eigen::Vector3d(-0.4, 0.6, 0)};
  const View view = rolling_view({Eigen::Vector2d(-0.35, 0.62)}, truth, FrameMotion{{1.0, 0, 0}, 1.5708});
  const PoseMotionFit found = fit(view, truth);
  EXPECT_TRUE(!found.ok || found.velocity_sigma > 0.2 || found.yaw_rate_sigma > 0.2)
      << "velocity sigma " << found.velocity_sigma << " m/s, yaw rate sigma " << found.yaw_rate_sigma << " rad/s";
}

// One marker, its dots 0.15 px noisy, and the fastest robot's motion as the prior (MAP): what the
// marker's rows show of the motion (its shear and stretch) moves the pose toward the one at t_ns,
// away from the plain fit (the pose at about the marker's rows' time); the covariance covers what
// they do not show, and the motion is never less certain than the fastest robot bounds it (without
// the prior, these dots leave the yaw rate's sigma above 90 deg/s). One noise draw decides little
// (the MAP fit is 0.8-8 mm off where the plain fit is 12 mm), so the claims are over 24 draws.
TEST(PoseMotionFit, OneMarkerWithTheFastestRobotAsPriorGivesThePoseAtTheFrameTimeWithinItsCovariance) {
  const RigidTransform truth{rotation_from_rpy(0, 0, -1.1), Eigen::Vector3d(-0.4, 0.6, 0)};
  const View exact = rolling_view({Eigen::Vector2d(-0.35, 0.62)}, truth, FrameMotion{{1.0, 0, 0}, 1.5708});
  const MotionLimits fastest;
  DrawErrors errors;
  for (unsigned seed = 1; seed <= 24; ++seed) {
    const View view = noisy(exact, seed);
    RefinementOptions options;
    options.dof = Dof::planar3;
    options.loss = RobustLoss::none;
    const PoseFit plain =
        refine_pose(view.world, view.pixels, CameraModel(board_camera()), up_mount(), truth, options);
    ASSERT_TRUE(plain.ok) << "draw " << seed;
    const PoseMotionFit found = fit_pose_and_motion(view.world, view.pixels, view.row_times, CameraModel(board_camera()),
                                                    up_mount(), plain.world_from_base, Dof::planar3, 0.05,
                                                    fastest_robot_prior(fastest));
    ASSERT_TRUE(found.ok) << "draw " << seed;
    EXPECT_LE(found.velocity_sigma, fastest.speed) << "draw " << seed;
    EXPECT_LE(found.yaw_rate_sigma, fastest.yaw_rate) << "draw " << seed;
    errors.add(plain.world_from_base, found, truth);
  }
  std::printf("plain fit %.2f mm RMS off, the MAP fit %.2f mm; its error over its sigma %.2f RMS\n",
              1e3 * errors.reference_rms(), 1e3 * errors.rms(), errors.normalized_rms());
  EXPECT_LT(errors.rms(), 0.5 * errors.reference_rms());
  EXPECT_LT(errors.normalized_rms(), 1.5);
}

// The same marker after a gap of 200 ms: the motion before the gap as the prior (the drive's own,
// its sigma grown with the gap: rolling_shutter.hpp, motion_prior_after_gap) gives poses closer to
// the one at t_ns than the fastest robot's zero-mean prior, still within their covariance. Over 24
// noise draws.
TEST(PoseMotionFit, OneMarkerAfterAGapWithTheMotionBeforeItAsPriorBeatsTheFastestRobotsPrior) {
  const RigidTransform truth{rotation_from_rpy(0, 0, -1.1), Eigen::Vector3d(-0.4, 0.6, 0)};
  const FrameMotion motion{{1.0, 0, 0}, 1.5708};
  const View exact = rolling_view({Eigen::Vector2d(-0.35, 0.62)}, truth, motion);
  const MotionLimits fastest;
  const std::optional<MotionPrior> after_gap = motion_prior_after_gap(motion, 0, 0, 0.2, fastest);
  ASSERT_TRUE(after_gap.has_value());
  DrawErrors errors;
  for (unsigned seed = 1; seed <= 24; ++seed) {
    const View view = noisy(exact, seed);
    const auto map_fit = [&](const MotionPrior& prior) {
      return fit_pose_and_motion(view.world, view.pixels, view.row_times, CameraModel(board_camera()), up_mount(),
                                 truth, Dof::planar3, 0.05, prior);
    };
    const PoseMotionFit with_fastest = map_fit(fastest_robot_prior(fastest));
    const PoseMotionFit found = map_fit(*after_gap);
    ASSERT_TRUE(with_fastest.ok && found.ok) << "draw " << seed;
    EXPECT_LE(found.velocity_sigma, after_gap->velocity_sigma) << "draw " << seed;
    EXPECT_LE(found.yaw_rate_sigma, after_gap->yaw_rate_sigma) << "draw " << seed;
    errors.add(with_fastest.world_from_base, found, truth);
  }
  std::printf("the fastest robot's prior: %.2f mm RMS off; the motion before the gap: %.2f mm, its error over its "
              "sigma %.2f RMS\n", 1e3 * errors.reference_rms(), 1e3 * errors.rms(), errors.normalized_rms());
  EXPECT_LT(errors.rms(), 0.75 * errors.reference_rms());
  EXPECT_LT(errors.normalized_rms(), 1.5);
}

// One marker half a metre ahead, seen by a robot that drives sideways at most 0.05 m/s
// (robot.max_side_speed: on wheels, its base origin on their axle): the marker's sideways shift
// over its rows is then the yaw rate's alone (a marker abeam or overhead shows it less), and the
// pose is nearer the one at t_ns than with the fastest robot's prior (2.0 mm RMS against 3.7 here),
// still within its covariance. Over 24 noise draws.
TEST(PoseMotionFit, OneMarkerOfARobotThatDoesNotDriveSidewaysGivesThePoseAtTheFrameTime) {
  const RigidTransform truth{rotation_from_rpy(0, 0, -1.1), Eigen::Vector3d(-0.4, 0.6, 0)};
  const View exact = rolling_view({Eigen::Vector2d(-0.17, 0.15)}, truth, FrameMotion{{1.0, 0, 0}, 1.5708});
  const MotionLimits any_way;
  MotionLimits on_wheels;
  on_wheels.side_speed = 0.05;
  DrawErrors errors;
  for (unsigned seed = 1; seed <= 24; ++seed) {
    const View view = noisy(exact, seed);
    const auto map_fit = [&](const MotionLimits& limits) {
      return fit_pose_and_motion(view.world, view.pixels, view.row_times, CameraModel(board_camera()), up_mount(),
                                 truth, Dof::planar3, 0.05, fastest_robot_prior(limits));
    };
    const PoseMotionFit sideways = map_fit(any_way);
    const PoseMotionFit found = map_fit(on_wheels);
    ASSERT_TRUE(sideways.ok && found.ok) << "draw " << seed;
    errors.add(sideways.world_from_base, found, truth);
  }
  std::printf("a robot that may drive any way: %.2f mm RMS off; one that does not drive sideways: %.2f mm, its error "
              "over its sigma %.2f RMS\n", 1e3 * errors.reference_rms(), 1e3 * errors.rms(), errors.normalized_rms());
  EXPECT_LT(errors.rms(), 0.75 * errors.reference_rms());
  EXPECT_LT(errors.normalized_rms(), 1.5);
}

TEST(PoseMotionFit, TooFewPointsIsNoFit) {
  const View view = rolling_view({Eigen::Vector2d(0.1, 0.0)}, RigidTransform{}, FrameMotion{});
  const std::vector<Eigen::Vector3d> two(view.world.begin(), view.world.begin() + 2);
  const std::vector<Eigen::Vector2d> two_pixels(view.pixels.begin(), view.pixels.begin() + 2);
  const std::vector<double> two_times(view.row_times.begin(), view.row_times.begin() + 2);
  EXPECT_FALSE(fit_pose_and_motion(two, two_pixels, two_times, CameraModel(board_camera()), up_mount(), RigidTransform{},
                                   Dof::planar3, 0.05, std::nullopt)
                   .ok);
}

}  // namespace
}  // namespace irloc
