#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "algo/markers/dot/mount_calibration.hpp"

namespace irloc::dot {
namespace {

// Poses of the camera axis while the robot spins about centre with the camera offset t.
std::vector<PlanarPose> spin(const Eigen::Vector2d& centre, const Eigen::Vector2d& t, double turn, int count,
                             double noise_m, unsigned seed = 4) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<PlanarPose> poses;
  for (int k = 0; k < count; ++k) {
    const double yaw = std::remainder(0.3 + turn * k / (count - 1), 2 * std::numbers::pi);
    const Eigen::Vector2d p = centre + Eigen::Rotation2Dd(yaw) * t;
    poses.push_back({p.x() + noise(random), p.y() + noise(random), yaw});
  }
  return poses;
}

TEST(MountCalibration, RecoversTheOffsetFromAFullSpin) {
  const Eigen::Vector2d centre(1.2, -0.4), offset(0.12, -0.05);
  const MountOffsetFit fit = fit_mount_offset(spin(centre, offset, 2 * std::numbers::pi, 120, 0.0005));
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.centre.x(), centre.x(), 0.001);
  EXPECT_NEAR(fit.centre.y(), centre.y(), 0.001);
  EXPECT_NEAR(fit.radius, offset.norm(), 0.001);
  EXPECT_NEAR(fit.offset.x(), offset.x(), 0.001);
  EXPECT_NEAR(fit.offset.y(), offset.y(), 0.001);
  EXPECT_LT(fit.circle_rms, 0.001);
}

TEST(MountCalibration, WorksFromHalfATurn) {
  const MountOffsetFit fit = fit_mount_offset(spin({0, 0}, {0.2, 0.0}, 1.1 * std::numbers::pi, 40, 0.0002));
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.offset.x(), 0.2, 0.002);
  EXPECT_NEAR(fit.offset.y(), 0.0, 0.002);
}

TEST(MountCalibration, RefusesTooLittleTurning) {
  EXPECT_FALSE(fit_mount_offset(spin({0, 0}, {0.1, 0.0}, 1.0, 50, 0.0)).ok);
  EXPECT_FALSE(fit_mount_offset(spin({0, 0}, {0.1, 0.0}, 7.0, 5, 0.0)).ok);
}

}  // namespace
}  // namespace irloc::dot
