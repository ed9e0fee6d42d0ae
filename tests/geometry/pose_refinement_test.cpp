// Pose refinement under dof 3, 4 and 6: convergence, constraints, robust losses, covariance.

#include "algo/geometry/pose_refinement.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/ceiling_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::up_mount;

RigidTransform truth_for(Dof dof) {
  switch (dof) {
    case Dof::planar3: return pose_from_parameters((PoseParameters() << 0.3, -0.2, 0, 0, 0, 2.5).finished());
    case Dof::height4: return pose_from_parameters((PoseParameters() << 0.3, -0.2, 0.12, 0, 0, -2.0).finished());
    case Dof::full6: return pose_from_parameters((PoseParameters() << 0.3, -0.2, 0.12, 0.03, -0.05, 1.0).finished());
  }
  return {};
}

class EveryDof : public ::testing::TestWithParam<Dof> {};
INSTANTIATE_TEST_SUITE_P(Dofs, EveryDof, ::testing::Values(Dof::planar3, Dof::height4, Dof::full6),
                         [](const auto& dof) { return "dof" + std::to_string(static_cast<int>(dof.param)); });

// A dot grid seen from truth_for(dof) with pixel noise, and a start well off the truth.
struct PerturbedScene {
  CameraModel camera{test::plumb_bob_lens()};
  RigidTransform truth;
  std::vector<Eigen::Vector3d> points = test::dot_grid(0.5, 0.1, 0.7);
  std::vector<Eigen::Vector2d> pixels;
  RigidTransform start;

  PerturbedScene(Dof dof, double noise_px, unsigned seed) : truth(truth_for(dof)) {
    std::mt19937 rng(seed);
    EXPECT_TRUE(test::observe(points, camera, truth, up_mount(), noise_px, rng, pixels));
    PoseParameters perturbed = parameters_from_pose(truth);
    perturbed += (PoseParameters() << 0.1, -0.08, 0.05, 0.02, -0.02, 0.2).finished();
    start = pose_from_parameters(perturbed);
  }
};

TEST_P(EveryDof, ConvergesFromAPerturbedPoseToTheTruth) {
  const PerturbedScene scene(GetParam(), 0, 1);
  RefinementOptions options;
  options.dof = GetParam();
  const PoseFit fit = refine_pose(scene.points, scene.pixels, scene.camera, up_mount(), scene.start, options);
  ASSERT_TRUE(fit.ok);
  EXPECT_LT((fit.world_from_base.translation - scene.truth.translation).norm(), 1e-8);
  EXPECT_LT(test::rotation_error(fit.world_from_base, scene.truth), 1e-9);
  EXPECT_LT(fit.rms_px, 1e-6);
}

TEST_P(EveryDof, ConstrainedParametersStayZeroAndHaveNoVariance) {
  const CameraModel camera(test::plumb_bob_lens());
  const RigidTransform truth = truth_for(Dof::full6);  // tilted: the constraints must hold anyway
  const auto points = test::dot_grid(0.5, 0.1, 0.7);
  std::mt19937 rng(2);
  std::vector<Eigen::Vector2d> pixels;
  ASSERT_TRUE(test::observe(points, camera, truth, up_mount(), 0.3, rng, pixels));
  RefinementOptions options;
  options.dof = GetParam();
  const PoseFit fit = refine_pose(points, pixels, camera, up_mount(), truth, options);
  ASSERT_TRUE(fit.ok);
  const PoseParameters p = parameters_from_pose(fit.world_from_base);
  const bool estimates_z = GetParam() != Dof::planar3, estimates_tilt = GetParam() == Dof::full6;
  if (!estimates_z) {
    EXPECT_EQ(p(2), 0);
  }
  if (!estimates_tilt) {
    EXPECT_NEAR(p(3), 0, 1e-15);
    EXPECT_NEAR(p(4), 0, 1e-15);
  }
  const std::array<bool, 6> free = {true, true, estimates_z, estimates_tilt, estimates_tilt, true};
  for (int k = 0; k < 6; ++k) {
    if (free[k]) {
      EXPECT_GT(fit.covariance(k, k), 0) << k;
    } else {
      EXPECT_EQ(fit.covariance.row(k).norm() + fit.covariance.col(k).norm(), 0) << k;
    }
  }
}

// With stop_step_sigmas the refinement stops in fewer iterations than at the cost's rounding floor,
// within that many standard deviations of the floor's minimum (its covariance's Mahalanobis
// distance, over the free parameters).
TEST_P(EveryDof, StopsWithinTheStepBoundOfTheMinimum) {
  const PerturbedScene scene(GetParam(), 0.1, 7);
  RefinementOptions options;
  options.dof = GetParam();
  const PoseFit to_floor = refine_pose(scene.points, scene.pixels, scene.camera, up_mount(), scene.start, options);
  options.stop_step_sigmas = 1e-3;
  const PoseFit stopped = refine_pose(scene.points, scene.pixels, scene.camera, up_mount(), scene.start, options);
  ASSERT_TRUE(to_floor.ok);
  ASSERT_TRUE(stopped.ok);
  EXPECT_LT(stopped.iterations, to_floor.iterations);
  PoseParameters difference =
      parameters_from_pose(stopped.world_from_base) - parameters_from_pose(to_floor.world_from_base);
  difference(5) = wrap_angle(difference(5));
  std::vector<int> free;
  for (int k = 0; k < 6; ++k) {
    if (to_floor.covariance(k, k) > 0) free.push_back(k);
  }
  const auto n = static_cast<Eigen::Index>(free.size());
  Eigen::MatrixXd covariance(n, n);
  Eigen::VectorXd d(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    d(i) = difference(free[static_cast<std::size_t>(i)]);
    for (Eigen::Index j = 0; j < n; ++j) {
      covariance(i, j) = to_floor.covariance(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]);
    }
  }
  const double sigmas = std::sqrt(d.dot(covariance.ldlt().solve(d)));
  std::printf("iterations %d (floor %d), %.2e standard deviations from the floor's minimum\n", stopped.iterations,
              to_floor.iterations, sigmas);
  EXPECT_LT(sigmas, 1e-3);
}

// The predicted covariance against the scatter of many noisy solutions.
// Two markers 1 m apart keep the problem close enough to linear for the covariance to be exact to
// first order (a single small marker under dof 6 is not: its tilt is uncertain by degrees).
TEST_P(EveryDof, CovarianceMatchesMonteCarloScatter) {
  const CameraModel camera(test::plumb_bob_lens());
  const RigidTransform truth = truth_for(GetParam());
  auto points = test::dot_grid(0.5, 0.1, 0.7);
  for (const auto& p : test::dot_grid(-0.3, 0.7, -0.4)) points.push_back(p);
  RefinementOptions options;
  options.dof = GetParam();
  options.loss = RobustLoss::none;
  options.pixel_sigma = 0.5;
  std::mt19937 rng(3);
  std::vector<Eigen::Vector2d> pixels;
  const PoseParameters truth_parameters = parameters_from_pose(truth);
  Eigen::Matrix<double, 6, 6> scatter = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> predicted;
  const int trials = 400;
  for (int t = 0; t < trials; ++t) {
    ASSERT_TRUE(test::observe(points, camera, truth, up_mount(), options.pixel_sigma, rng, pixels));
    const PoseFit fit = refine_pose(points, pixels, camera, up_mount(), truth, options);
    ASSERT_TRUE(fit.ok);
    PoseParameters error = parameters_from_pose(fit.world_from_base) - truth_parameters;
    error(5) = wrap_angle(error(5));
    scatter += error * error.transpose() / trials;
    predicted = fit.covariance;
  }
  for (int k = 0; k < 6; ++k) {
    if (predicted(k, k) == 0) continue;
    const double ratio = scatter(k, k) / predicted(k, k);
    std::printf("parameter %d: scatter / predicted variance %.3f\n", k, ratio);
    EXPECT_GT(ratio, 0.75) << "parameter " << k;
    EXPECT_LT(ratio, 1.33) << "parameter " << k;
  }
}

TEST(PoseRefinement, RobustLossesResistAnOutlier) {
  const CameraModel camera(test::plumb_bob_lens());
  const RigidTransform truth = truth_for(Dof::planar3);
  const auto points = test::dot_grid(0.5, 0.1, 0.7);
  std::mt19937 rng(4);
  std::vector<Eigen::Vector2d> pixels;
  ASSERT_TRUE(test::observe(points, camera, truth, up_mount(), 0.2, rng, pixels));
  // The reference: least squares without the dot that is about to go wrong.
  auto without_outlier_points = points;
  auto without_outlier_pixels = pixels;
  without_outlier_points.erase(without_outlier_points.begin() + 5);
  without_outlier_pixels.erase(without_outlier_pixels.begin() + 5);
  RefinementOptions plain_options;
  plain_options.loss = RobustLoss::none;
  const Eigen::Vector3d reference =
      refine_pose(without_outlier_points, without_outlier_pixels, camera, up_mount(), truth, plain_options)
          .world_from_base.translation;
  pixels[5] += Eigen::Vector2d(40, -25);  // a misdetected dot
  auto distance_from_reference = [&](RobustLoss loss) {
    RefinementOptions options;
    options.loss = loss;
    const PoseFit fit = refine_pose(points, pixels, camera, up_mount(), truth, options);
    EXPECT_TRUE(fit.ok);
    return (fit.world_from_base.translation - reference).norm();
  };
  const double plain = distance_from_reference(RobustLoss::none);
  const double huber = distance_from_reference(RobustLoss::huber);
  const double cauchy = distance_from_reference(RobustLoss::cauchy);
  std::printf("distance from the outlier-free fit: none %.2e, huber %.2e, cauchy %.2e m\n", plain, huber, cauchy);
  EXPECT_GT(plain, 5e-3);
  EXPECT_LT(huber, 0.5 * plain);
  EXPECT_LT(cauchy, 0.05 * plain);
}

TEST(PoseRefinement, RejectsTooFewPointsAndPointsOutsideTheView) {
  const CameraModel camera(test::plumb_bob_lens());
  const RigidTransform truth = truth_for(Dof::full6);
  const auto points = test::dot_grid(0.5, 0.1, 0.7);
  std::mt19937 rng(5);
  std::vector<Eigen::Vector2d> pixels;
  ASSERT_TRUE(test::observe(points, camera, truth, up_mount(), 0, rng, pixels));
  RefinementOptions options;
  options.dof = Dof::full6;
  EXPECT_FALSE(refine_pose(std::span(points).first(2), std::span(pixels).first(2), camera, up_mount(), truth, options).ok);
  EXPECT_TRUE(refine_pose(std::span(points).first(3), std::span(pixels).first(3), camera, up_mount(), truth, options).ok);
  RigidTransform upside_down = truth;
  upside_down.rotation = rotation_from_rpy(3.1, 0, 0);
  EXPECT_FALSE(refine_pose(points, pixels, camera, up_mount(), upside_down, options).ok);
}

TEST(PoseRefinement, AllocatesNothing) {
  const CameraModel camera(test::equisolid_lens());
  const RigidTransform truth = truth_for(Dof::full6);
  const auto points = test::dot_grid(0.5, 0.1, 0.7);
  std::mt19937 rng(6);
  std::vector<Eigen::Vector2d> pixels;
  ASSERT_TRUE(test::observe(points, camera, truth, up_mount(), 0.3, rng, pixels));
  RefinementOptions options;
  options.dof = Dof::full6;
  test::AllocationCounter counter;
  const PoseFit fit = refine_pose(points, pixels, camera, up_mount(), truth, options);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(fit.ok);
}

}  // namespace
}  // namespace irloc
