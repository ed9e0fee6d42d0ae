// Fusion of two level poses, and the point-fit uncertainty model used for the dot path's share.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "algo/pipeline/pose_fusion.hpp"

namespace irloc {
namespace {

TEST(PoseFusion, WeightsByInverseVariance) {
  const LevelPose a{1.00, 2.00, 0.0, 0.10, 0.002, 0.01};
  const LevelPose b{1.03, 1.97, 0.0, 0.12, 0.004, 0.01};
  LevelPose fused;
  ASSERT_TRUE(fuse_level_poses(a, b, FusionGate{}, fused));
  // a has four times b's weight: 1/5 of the way from a to b.
  EXPECT_NEAR(fused.x, 1.006, 1e-12);
  EXPECT_NEAR(fused.y, 1.994, 1e-12);
  EXPECT_NEAR(fused.yaw, 0.11, 1e-12);  // equal yaw weights
  EXPECT_NEAR(fused.position_sigma, 1 / std::sqrt(1 / 4e-6 + 1 / 16e-6), 1e-12);
  EXPECT_NEAR(fused.yaw_sigma, 0.01 / std::sqrt(2.0), 1e-12);
}

TEST(PoseFusion, AveragesYawAcrossTheWrap) {
  const double pi = std::numbers::pi;
  const LevelPose a{0, 0, 0, pi - 0.01, 0.01, 0.01};
  const LevelPose b{0, 0, 0, -pi + 0.01, 0.01, 0.01};
  LevelPose fused;
  ASSERT_TRUE(fuse_level_poses(a, b, FusionGate{}, fused));
  EXPECT_NEAR(std::abs(fused.yaw), pi, 1e-12);
}

TEST(PoseFusion, DisagreementGivesNoPose) {
  const LevelPose a{0, 0, 0, 0, 0.01, 0.01};
  LevelPose fused;
  EXPECT_FALSE(fuse_level_poses(a, LevelPose{0.15, 0, 0, 0, 0.01, 0.01}, FusionGate{}, fused));
  EXPECT_FALSE(fuse_level_poses(a, LevelPose{0, 0, 0, 0.1, 0.01, 0.01}, FusionGate{}, fused));
  EXPECT_FALSE(fuse_level_poses(a, LevelPose{0, 0, 0, 0, 0, 0.01}, FusionGate{}, fused));  // no sigma
}

// The model's sigmas against a Monte-Carlo of a 2-D rigid fit (closed form) to noisy points.
TEST(PoseFusion, PointFitUncertaintyMatchesMonteCarlo) {
  const std::array<Eigen::Vector2d, 6> points{Eigen::Vector2d(0, 0),    Eigen::Vector2d(0.12, 0),
                                              Eigen::Vector2d(0, 0.12), Eigen::Vector2d(0.04, 0.04),
                                              Eigen::Vector2d(0.08, 0), Eigen::Vector2d(0.04, 0.08)};
  const std::array<double, 6> footprints{0.006, 0.006, 0.006, 0.006, 0.006, 0.006};
  const double sigma_px = 0.5;
  LevelPose model;
  point_fit_uncertainty(footprints, points, sigma_px, model);

  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, sigma_px * 0.006);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p / 6.0;
  double sum_x = 0, sum_yaw = 0;
  constexpr int kTrials = 20000;
  for (int trial = 0; trial < kTrials; ++trial) {
    Eigen::Vector2d measured_centroid = Eigen::Vector2d::Zero();
    std::array<Eigen::Vector2d, 6> measured;
    for (std::size_t i = 0; i < 6; ++i) {
      measured[i] = points[i] + Eigen::Vector2d(noise(rng), noise(rng));
      measured_centroid += measured[i] / 6.0;
    }
    double dot = 0, cross = 0;
    for (std::size_t i = 0; i < 6; ++i) {
      const Eigen::Vector2d a = points[i] - centroid, b = measured[i] - measured_centroid;
      dot += a.dot(b);
      cross += a.x() * b.y() - a.y() * b.x();
    }
    sum_x += std::pow(measured_centroid.x() - centroid.x(), 2);
    sum_yaw += std::pow(std::atan2(cross, dot), 2);
  }
  EXPECT_NEAR(model.position_sigma, std::sqrt(sum_x / kTrials), 0.05 * model.position_sigma);
  EXPECT_NEAR(model.yaw_sigma, std::sqrt(sum_yaw / kTrials), 0.1 * model.yaw_sigma);
}

}  // namespace
}  // namespace irloc
