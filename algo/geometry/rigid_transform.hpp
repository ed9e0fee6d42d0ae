#pragma once
// A rigid transform T_A_B (rotation + translation) mapping B coordinates to A coordinates:
// p_A = rotation * p_B + translation. Metres.

#include <Eigen/Core>

namespace irloc {

struct RigidTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& point) const { return rotation * point + translation; }
  // T_A_B * T_B_C = T_A_C.
  RigidTransform operator*(const RigidTransform& other) const {
    return {rotation * other.rotation, rotation * other.translation + translation};
  }
  RigidTransform inverse() const {
    const Eigen::Matrix3d transposed = rotation.transpose();
    return {transposed, -(transposed * translation)};
  }
};

}  // namespace irloc
