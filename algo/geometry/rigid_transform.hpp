#pragma once
// A rigid transform T_A_B (rotation + translation) mapping B coordinates to A coordinates:
// p_A = rotation * p_B + translation. Metres.

#include <Eigen/Geometry>

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

// The same transform held as an Eigen isometry (the simulator's and the tests' type).
inline RigidTransform to_rigid(const Eigen::Isometry3d& transform) { return {transform.linear(), transform.translation()}; }
inline Eigen::Isometry3d to_isometry(const RigidTransform& transform) {
  Eigen::Isometry3d isometry = Eigen::Isometry3d::Identity();
  isometry.linear() = transform.rotation;
  isometry.translation() = transform.translation;
  return isometry;
}

}  // namespace irloc
