// solve_planar_pnp on random planar problems through distorted lenses: exact without noise, a
// least-squares minimum with it, and its information matrix consistent with the spread of the
// poses it gives.
#include "algo/geometry/planar_pnp.hpp"

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/planar_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

TEST(PlanarPnp, RecoversThePoseExactlyWithoutNoise) {
  std::mt19937 rng(3);
  for (const CameraIntrinsics& lens : {test::plumb_bob_lens(), test::wide_plumb_bob_lens(), test::equidistant_lens()}) {
    const CameraModel camera(lens);
    int solved = 0;
    for (int trial = 0; trial < 400; ++trial) {
      test::PlanarProblem problem;
      const int side = 2 + trial % 3;  // 4, 9 and 16 points
      if (!test::make_planar_problem(camera, side, side, 0.6 / (side - 1), 0, rng, problem)) continue;
      const PlanarPose pose = solve_planar_pnp(problem.plane, problem.pixels, camera);
      ASSERT_TRUE(pose.ok) << trial;
      EXPECT_LT(test::rotation_error(pose.camera_from_plane, problem.camera_from_plane), 1e-7) << trial;
      EXPECT_LT(test::centre_error(pose.camera_from_plane, problem.camera_from_plane), 1e-6) << trial;
      EXPECT_LT(pose.sum_squares_px2, 1e-12) << trial;
      ++solved;
    }
    EXPECT_GT(solved, 100);
  }
}

// With noise the answer is a minimum of the reprojection error: no better than the truth would
// be an accident, and small steps away from it never lower the error.
TEST(PlanarPnp, FindsTheLeastSquaresPoseWithNoise) {
  std::mt19937 rng(5);
  const CameraModel camera(test::plumb_bob_lens());
  const auto sum_squares = [&](const RigidTransform& pose, const test::PlanarProblem& problem) {
    double sum = 0;
    for (std::size_t i = 0; i < problem.plane.size(); ++i) {
      Eigen::Vector2d pixel;
      camera.project(pose * Eigen::Vector3d(problem.plane[i].x(), problem.plane[i].y(), 0), pixel);
      sum += (pixel - problem.pixels[i]).squaredNorm();
    }
    return sum;
  };
  int solved = 0;
  for (int trial = 0; trial < 300; ++trial) {
    test::PlanarProblem problem;
    if (!test::make_planar_problem(camera, 3, 3, 0.3, 0.5, rng, problem)) continue;
    const PlanarPose pose = solve_planar_pnp(problem.plane, problem.pixels, camera);
    ASSERT_TRUE(pose.ok);
    EXPECT_NEAR(pose.sum_squares_px2, sum_squares(pose.camera_from_plane, problem), 1e-9);
    EXPECT_LE(pose.sum_squares_px2, sum_squares(problem.camera_from_plane, problem) + 1e-9) << trial;
    for (int k = 0; k < 6; ++k) {
      for (const double step : {-1e-4, 1e-4}) {
        RigidTransform moved = pose.camera_from_plane;
        if (k < 3) moved.rotation = Eigen::AngleAxisd(step, Eigen::Vector3d::Unit(k)) * moved.rotation;
        else moved.translation(k - 3) += step;
        EXPECT_GE(sum_squares(moved, problem), pose.sum_squares_px2 - 1e-9) << trial << " " << k;
      }
    }
    ++solved;
  }
  EXPECT_GT(solved, 100);
}

// sigma^2 times the inverse information predicts the spread of the camera's position over
// repeated noise on one problem (a 0.6 m tile 3-4 m away, the floor reference's case).
TEST(PlanarPnp, ItsInformationPredictsTheSpreadOfThePose) {
  std::mt19937 rng(11);
  const CameraModel camera(test::plumb_bob_lens());
  test::PlanarProblem problem;
  while (!test::make_planar_problem(camera, 2, 2, 0.6, 0, rng, problem)) {}
  constexpr double kSigma = 0.3;
  std::normal_distribution<double> noise(0, kSigma);
  Eigen::Matrix<double, 6, 6> scatter = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> predicted = Eigen::Matrix<double, 6, 6>::Zero();
  constexpr int kTrials = 2000;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::vector<Eigen::Vector2d> pixels = problem.pixels;
    for (Eigen::Vector2d& pixel : pixels) pixel += Eigen::Vector2d(noise(rng), noise(rng));
    const PlanarPose pose = solve_planar_pnp(problem.plane, pixels, camera);
    ASSERT_TRUE(pose.ok);
    Eigen::Matrix<double, 6, 1> error;
    error.head<3>() = Eigen::AngleAxisd(pose.camera_from_plane.rotation * problem.camera_from_plane.rotation.transpose())
                          .angle() *
                      Eigen::AngleAxisd(pose.camera_from_plane.rotation * problem.camera_from_plane.rotation.transpose()).axis();
    error.tail<3>() = pose.camera_from_plane.translation - problem.camera_from_plane.translation;
    scatter += error * error.transpose();
    if (trial == 0) predicted = kSigma * kSigma * pose.information.inverse();
  }
  scatter /= kTrials;
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(std::sqrt(scatter(k, k) / predicted(k, k)), 1, 0.2) << k;
}

TEST(PlanarPnp, RefusesTooFewPointsAndAllocatesNothing) {
  const CameraModel camera(test::plumb_bob_lens());
  std::mt19937 rng(2);
  test::PlanarProblem problem;
  while (!test::make_planar_problem(camera, 3, 3, 0.2, 0.2, rng, problem)) {}
  EXPECT_FALSE(solve_planar_pnp(std::span(problem.plane).first(3), std::span(problem.pixels).first(3), camera).ok);
  test::AllocationCounter allocations;
  EXPECT_TRUE(solve_planar_pnp(problem.plane, problem.pixels, camera).ok);
  EXPECT_EQ(allocations.count(), 0u);
}

}  // namespace
}  // namespace irloc
