// Fusion of several sources' poses by their covariances, and the covariance of a level fit to
// ceiling points (the square source's) against a Monte Carlo.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "algo/geometry/planar_fit.hpp"
#include "algo/pipeline/pose_fusion.hpp"

namespace irloc {
namespace {

// A level source result at (x, y, yaw), with independent sigmas on x and y and on yaw.
SourceResult level_result(double x, double y, double yaw, double position_sigma, double yaw_sigma) {
  SourceResult result;
  result.ok = true;
  result.world_from_base.rotation = rotation_from_rpy(0, 0, yaw);
  result.world_from_base.translation = Eigen::Vector3d(x, y, 0);
  result.covariance(0, 0) = result.covariance(1, 1) = position_sigma * position_sigma;
  result.covariance(5, 5) = yaw_sigma * yaw_sigma;
  return result;
}

bool fuse_two(const SourceResult& a, const SourceResult& b, FusedPose& fused) {
  const std::array<const SourceResult*, 2> results{&a, &b};
  return fuse_poses(results, Dof::planar3, FusionGate{}, fused);
}

TEST(PoseFusion, WeightsByInverseVariance) {
  const SourceResult a = level_result(1.00, 2.00, 0.10, 0.002, 0.01);
  const SourceResult b = level_result(1.03, 1.97, 0.12, 0.004, 0.01);
  FusedPose fused;
  ASSERT_TRUE(fuse_two(a, b, fused));
  // a has four times b's weight: 1/5 of the way from a to b.
  EXPECT_NEAR(fused.world_from_base.translation.x(), 1.006, 1e-12);
  EXPECT_NEAR(fused.world_from_base.translation.y(), 1.994, 1e-12);
  EXPECT_NEAR(rpy_from_rotation(fused.world_from_base.rotation).yaw, 0.11, 1e-12);  // equal yaw weights
  EXPECT_NEAR(std::sqrt(fused.covariance(0, 0)), 1 / std::sqrt(1 / 4e-6 + 1 / 16e-6), 1e-12);
  EXPECT_NEAR(std::sqrt(fused.covariance(5, 5)), 0.01 / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(fused.covariance(2, 2), 0);  // z is not estimated under dof 3
}

TEST(PoseFusion, AveragesYawAcrossTheWrap) {
  const double pi = std::numbers::pi;
  FusedPose fused;
  ASSERT_TRUE(fuse_two(level_result(0, 0, pi - 0.01, 0.01, 0.01), level_result(0, 0, -pi + 0.01, 0.01, 0.01), fused));
  EXPECT_NEAR(std::abs(rpy_from_rotation(fused.world_from_base.rotation).yaw), pi, 1e-12);
}

TEST(PoseFusion, DisagreementGivesNoPose) {
  const SourceResult a = level_result(0, 0, 0, 0.01, 0.01);
  FusedPose fused;
  EXPECT_FALSE(fuse_two(a, level_result(0.15, 0, 0, 0.01, 0.01), fused));
  EXPECT_FALSE(fuse_two(a, level_result(0, 0, 0.1, 0.01, 0.01), fused));
  EXPECT_FALSE(fuse_two(a, level_result(0, 0, 0, 0, 0.01), fused));  // no sigma
}

// Correlated covariances: the fused mean is (sum C_i^-1)^-1 sum C_i^-1 p_i, not a per-axis mean.
TEST(PoseFusion, UsesTheCrossTerms) {
  SourceResult a = level_result(0.00, 0.00, 0.0, 0.01, 0.01);
  SourceResult b = level_result(0.02, 0.00, 0.0, 0.01, 0.01);
  a.covariance(0, 1) = a.covariance(1, 0) = 0.9e-4;  // a is sure only of x - y
  FusedPose fused;
  ASSERT_TRUE(fuse_two(a, b, fused));
  const Eigen::Matrix2d ca = a.covariance.topLeftCorner<2, 2>(), cb = b.covariance.topLeftCorner<2, 2>();
  const Eigen::Matrix2d information = ca.inverse() + cb.inverse();
  const Eigen::Vector2d expected = information.inverse() * (cb.inverse() * Eigen::Vector2d(0.02, 0));
  EXPECT_NEAR(fused.world_from_base.translation.x(), expected.x(), 1e-12);
  EXPECT_NEAR(fused.world_from_base.translation.y(), expected.y(), 1e-12);
  EXPECT_GT(std::abs(fused.world_from_base.translation.y()), 1e-3);  // b's x pulls a's y along
  EXPECT_NEAR(fused.covariance(0, 1), information.inverse()(0, 1), 1e-15);
}

// The model's covariance against a Monte Carlo of the 2-D rigid fit (closed form) of four noisy
// corners seen from a level robot.
TEST(PoseFusion, LevelFitCovarianceMatchesMonteCarlo) {
  const std::array<Eigen::Vector2d, 4> in_base{Eigen::Vector2d(0.6, 0.9), Eigen::Vector2d(0.7, -1.1),
                                               Eigen::Vector2d(-1.3, -1.0), Eigen::Vector2d(-1.4, 1.0)};
  const double yaw = 0.7, sigma = 0.003;
  const Eigen::Vector2d position(2.0, -1.0);
  const Eigen::Matrix<double, 6, 6> model =
      level_fit_covariance(in_base, Eigen::Vector2d::Zero(), 2.0, yaw, sigma, Dof::planar3);

  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, sigma);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  constexpr int kTrials = 20000;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::array<Eigen::Vector2d, 4> measured;
    for (std::size_t i = 0; i < 4; ++i) measured[i] = rotation * in_base[i] + position + Eigen::Vector2d(noise(rng), noise(rng));
    PlanarTransform fit;
    ASSERT_TRUE(fit_rigid_2d(in_base, measured, fit));
    const Eigen::Vector3d error(fit.translation.x() - position.x(), fit.translation.y() - position.y(),
                                wrap_angle(fit.yaw - yaw));
    scatter += error * error.transpose() / kTrials;
  }
  constexpr int kIndex[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(model(kIndex[i], kIndex[i])), std::sqrt(scatter(i, i)), 0.03 * std::sqrt(scatter(i, i)));
  }
  // The lever arm of the corners' centroid couples position and yaw.
  EXPECT_NEAR(model(0, 5), scatter(0, 2), 0.1 * std::sqrt(scatter(0, 0) * scatter(2, 2)));
  EXPECT_NEAR(model(1, 5), scatter(1, 2), 0.1 * std::sqrt(scatter(1, 1) * scatter(2, 2)));
}

}  // namespace
}  // namespace irloc
