#include "firmware/protocol/ned_frame.hpp"

#include "algo/geometry/pose.hpp"

namespace irloc::firmware {

NedPose ned_from_world(const PoseEstimate& estimate) {
  NedPose ned;
  ned.north = estimate.x;
  ned.east = -estimate.y;
  ned.down = -estimate.z;
  ned.roll = wrap_angle(estimate.roll);
  ned.pitch = -estimate.pitch;
  ned.yaw = wrap_angle(-estimate.yaw);
  return ned;
}

PoseCovariance ned_covariance(const PoseCovariance& world) {
  const Eigen::Matrix<double, 6, 1> signs = (Eigen::Matrix<double, 6, 1>() << 1, -1, -1, 1, -1, -1).finished();
  return signs.asDiagonal() * world * signs.asDiagonal();
}

}  // namespace irloc::firmware
