#include "algo/geometry/pose.hpp"

#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace irloc {
namespace {

constexpr double pi = std::numbers::pi;

TEST(Pose, RollPitchYawIsFixedAxesXThenYThenZ) {
  // Yaw alone turns base x toward world y.
  const Eigen::Vector3d x_in_w = rotation_from_rpy(0, 0, pi / 2) * Eigen::Vector3d::UnitX();
  EXPECT_TRUE(x_in_w.isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  // Roll first, then pitch, then yaw: R = Rz Ry Rx.
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                                   Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                                   Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_TRUE(rotation_from_rpy(0.1, 0.2, 0.3).isApprox(expected, 1e-12));
}

TEST(Pose, RpyRoundTrips) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> angle(-pi, pi);
  std::uniform_real_distribution<double> pitch(-pi / 2 + 1e-3, pi / 2 - 1e-3);
  for (int i = 0; i < 10000; ++i) {
    const double r = angle(random), p = pitch(random), y = angle(random);
    const RollPitchYaw rpy = rpy_from_rotation(rotation_from_rpy(r, p, y));
    ASSERT_NEAR(wrap_angle(rpy.roll - r), 0, 1e-9);
    ASSERT_NEAR(rpy.pitch, p, 1e-9);
    ASSERT_NEAR(wrap_angle(rpy.yaw - y), 0, 1e-9);
  }
}

TEST(Pose, WrapsYawToMinusPiExclusivePiInclusive) {
  EXPECT_DOUBLE_EQ(wrap_angle(pi), pi);
  EXPECT_DOUBLE_EQ(wrap_angle(-pi), pi);
  EXPECT_NEAR(wrap_angle(3 * pi / 2), -pi / 2, 1e-12);
  EXPECT_NEAR(wrap_angle(-5 * pi / 2), -pi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_angle(0.25), 0.25);
}

}  // namespace
}  // namespace irloc
