// The world (z up) to NED conversion, against the rotation it claims to be: R_NED = F R_W_B F
// with F = diag(1, -1, -1), built and decomposed with Eigen and algo/geometry.

#include <cmath>
#include <numbers>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "algo/geometry/pose.hpp"
#include "firmware/protocol/ned_frame.hpp"

namespace irloc::firmware {
namespace {

TEST(NedFrame, MatchesTheHalfTurnAboutXForPositionsAndAttitudes) {
  const Eigen::Matrix3d flip = Eigen::Vector3d(1, -1, -1).asDiagonal();
  const double angles[] = {-2.9, -1.2, -0.3, 0.0, 0.4, 1.3, 3.0};
  for (const double roll : {-0.3, 0.0, 0.2}) {
    for (const double pitch : {-0.4, 0.0, 0.35}) {
      for (const double yaw : angles) {
        PoseEstimate pose;
        pose.x = 1.5;
        pose.y = -2.25;
        pose.z = 0.75;
        pose.roll = roll;
        pose.pitch = pitch;
        pose.yaw = yaw;
        const NedPose ned = ned_from_world(pose);
        const Eigen::Vector3d position = flip * Eigen::Vector3d(pose.x, pose.y, pose.z);
        EXPECT_DOUBLE_EQ(ned.north, position.x());
        EXPECT_DOUBLE_EQ(ned.east, position.y());
        EXPECT_DOUBLE_EQ(ned.down, position.z());
        const RollPitchYaw expected = rpy_from_rotation(flip * rotation_from_rpy(roll, pitch, yaw) * flip);
        EXPECT_NEAR(ned.roll, expected.roll, 1e-12);
        EXPECT_NEAR(ned.pitch, expected.pitch, 1e-12);
        EXPECT_NEAR(std::remainder(ned.yaw - expected.yaw, 2 * std::numbers::pi), 0.0, 1e-12);
      }
    }
  }
}

TEST(NedFrame, FacingWorldPlusYIsHeadingWest) {
  PoseEstimate pose;
  pose.yaw = std::numbers::pi / 2;  // facing W +y, which is NED -east
  EXPECT_NEAR(ned_from_world(pose).yaw, -std::numbers::pi / 2, 1e-12);
}

}  // namespace
}  // namespace irloc::firmware
