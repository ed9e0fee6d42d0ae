#pragma once
// Four-parameter poses of frames whose z axis is W's z (a level robot, a ceiling marker's level
// frame): (x, y, z, yaw). A dot marker's level frame L has M's origin and x axis and W's z; the
// map's M is L turned half a turn about x (docs/formats.md).

#include <Eigen/Core>

#include "algo/geometry/rigid_transform.hpp"

namespace irloc::survey {

using CeilingPose = Eigen::Vector4d;  // x, y, z, yaw
using CeilingCovariance = Eigen::Matrix4d;
using CeilingJacobian = Eigen::Matrix4d;

// b in a's frame: T_A_B = T_W_A^-1 T_W_B. The Jacobians (optional) are d relative / d a and d b.
CeilingPose relative_pose(const CeilingPose& a, const CeilingPose& b, CeilingJacobian* d_a = nullptr,
                          CeilingJacobian* d_b = nullptr);
// T_W_A T_A_B.
CeilingPose compose(const CeilingPose& a, const CeilingPose& a_to_b);
// b - a with the yaw difference wrapped to (-pi, pi].
CeilingPose pose_difference(const CeilingPose& b, const CeilingPose& a);

RigidTransform to_transform(const CeilingPose& pose);
// (x, y, z, yaw) of a transform whose rotation is (close to) a turn about z.
CeilingPose ceiling_pose_from(const RigidTransform& transform);

}  // namespace irloc::survey
