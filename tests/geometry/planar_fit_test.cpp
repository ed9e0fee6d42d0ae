// Closed-form 2-D fits and the level-robot ceiling pose, against the steepest-descent
// formulation of the square-marker paper as an independent reference.

#include "algo/geometry/planar_fit.hpp"

#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/ceiling_scene.hpp"

namespace irloc {
namespace {

// Reference only (the square-marker paper's formulation): steepest descent on
// E(yaw, t) = sum |R(yaw) from_i + t - to_i|^2 with a fixed step, from the zero transform.
PlanarTransform steepest_descent_fit(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to) {
  double yaw = 0;
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double spread = 0;
  for (const auto& p : from) spread += p.squaredNorm();
  const double n = static_cast<double>(from.size());
  for (int iteration = 0; iteration < 200000; ++iteration) {
    const Eigen::Rotation2Dd rotation(yaw);
    const Eigen::Matrix2d d_rotation = (Eigen::Matrix2d() << -std::sin(yaw), -std::cos(yaw), std::cos(yaw), -std::sin(yaw)).finished();
    double d_yaw = 0;
    Eigen::Vector2d d_t = Eigen::Vector2d::Zero();
    for (std::size_t i = 0; i < from.size(); ++i) {
      const Eigen::Vector2d r = rotation * from[i] + t - to[i];
      d_yaw += 2 * r.dot(d_rotation * from[i]);
      d_t += 2 * r;
    }
    yaw -= 0.25 * d_yaw / spread;
    t -= 0.25 * d_t / n;
    if (std::abs(d_yaw) / spread + d_t.norm() / n < 1e-13) break;
  }
  return {yaw, 1, t};
}

TEST(PlanarFit, RigidFitAgreesWithSteepestDescent) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::normal_distribution<double> noise(0, 0.01);
  for (int trial = 0; trial < 20; ++trial) {
    const double yaw = 1.2 * unit(rng);  // within the basin of the descent started at 0
    const Eigen::Vector2d t(unit(rng), unit(rng));
    std::vector<Eigen::Vector2d> from, to;
    for (int i = 0; i < 6; ++i) {
      from.emplace_back(unit(rng), unit(rng));
      to.push_back(Eigen::Rotation2Dd(yaw) * from.back() + t + Eigen::Vector2d(noise(rng), noise(rng)));
    }
    PlanarTransform fit;
    ASSERT_TRUE(fit_rigid_2d(from, to, fit));
    const PlanarTransform reference = steepest_descent_fit(from, to);
    EXPECT_NEAR(fit.yaw, reference.yaw, 1e-9);
    EXPECT_LT((fit.translation - reference.translation).norm(), 1e-9);
    EXPECT_EQ(fit.scale, 1);
    EXPECT_NEAR(fit.yaw, yaw, 0.05);
  }
}

TEST(PlanarFit, SimilarityFitRecoversScaleExactly) {
  const std::vector<Eigen::Vector2d> from = {{0, 0}, {1, 0}, {0, 2}, {-1, 1}};
  std::vector<Eigen::Vector2d> to;
  for (const auto& p : from) to.push_back(2.5 * (Eigen::Rotation2Dd(-2.9) * p) + Eigen::Vector2d(3, -4));
  PlanarTransform fit;
  ASSERT_TRUE(fit_similarity_2d(from, to, fit));
  EXPECT_NEAR(fit.scale, 2.5, 1e-12);
  EXPECT_NEAR(fit.yaw, -2.9, 1e-12);
  EXPECT_LT((fit.translation - Eigen::Vector2d(3, -4)).norm(), 1e-12);
}

TEST(PlanarFit, DegenerateInputIsRefused) {
  PlanarTransform fit;
  const std::vector<Eigen::Vector2d> one = {{1, 1}}, two_same = {{1, 1}, {1, 1}}, two = {{0, 0}, {1, 0}};
  EXPECT_FALSE(fit_rigid_2d(one, one, fit));
  EXPECT_FALSE(fit_rigid_2d(two_same, two, fit));
  EXPECT_FALSE(fit_similarity_2d(two, one, fit));
}

TEST(PlanarFit, LevelPoseFromCeilingIsExactWithoutNoise) {
  const CameraModel camera(test::equisolid_lens());
  for (Dof dof : {Dof::planar3, Dof::height4}) {
    const RigidTransform truth{rotation_from_rpy(0, 0, -2.2), Eigen::Vector3d(0.4, 0.7, dof == Dof::planar3 ? 0 : 0.25)};
    const auto points = test::dot_grid(1.0, 0.2, 0.3);
    std::mt19937 rng(2);
    std::vector<Eigen::Vector2d> pixels;
    ASSERT_TRUE(test::observe(points, camera, truth, test::up_mount(), 0, rng, pixels));
    std::vector<Eigen::Vector3d> bearings;
    for (const auto& pixel : pixels) {
      ASSERT_TRUE(camera.unproject(pixel, bearings.emplace_back()));
    }
    RigidTransform pose;
    ASSERT_TRUE(level_pose_from_ceiling(points, bearings, test::kCeilingZ, test::up_mount(), dof, pose));
    EXPECT_LT((pose.translation - truth.translation).norm(), 1e-9);
    EXPECT_LT(test::rotation_error(pose, truth), 1e-9);
    EXPECT_FALSE(level_pose_from_ceiling(points, bearings, test::kCeilingZ, test::up_mount(), Dof::full6, pose));
  }
}

}  // namespace
}  // namespace irloc
