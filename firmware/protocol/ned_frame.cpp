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

Eigen::Quaterniond ned_attitude(const NedPose& ned) {
  return Eigen::Quaterniond(rotation_from_rpy(ned.roll, ned.pitch, ned.yaw)).normalized();
}

FrdVelocity frd_velocity(const PoseEstimate& estimate, const PoseVelocity& velocity) {
  const Eigen::Matrix3d flip = Eigen::Vector3d(1, -1, -1).asDiagonal();
  const Eigen::Matrix3d body_from_world = flip * rotation_from_rpy(estimate.roll, estimate.pitch, estimate.yaw).transpose();
  Eigen::Matrix4d map = Eigen::Matrix4d::Zero();
  map.topLeftCorner<3, 3>() = body_from_world;
  map(3, 3) = -1;
  FrdVelocity frd;
  frd.velocity = body_from_world * velocity.world;
  frd.heading_rate = -velocity.yaw_rate;
  frd.covariance = map * velocity.covariance * map.transpose();
  return frd;
}

}  // namespace irloc::firmware
