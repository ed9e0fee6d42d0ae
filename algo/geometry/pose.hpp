#pragma once
// Rigid transforms and the roll-pitch-yaw convention of docs/conventions.md.

#include <Eigen/Geometry>

#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

// R = Rz(yaw) Ry(pitch) Rx(roll): fixed axes X, then Y, then Z.
Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw);

struct RollPitchYaw {
  double roll = 0, pitch = 0, yaw = 0;
};
// The inverse of rotation_from_rpy with pitch in [-pi/2, pi/2] and yaw in (-pi, pi].
RollPitchYaw rpy_from_rotation(const Eigen::Matrix3d& rotation);

// The heading (yaw) of a base pose T_W_B, rpy_from_rotation's yaw alone: rad in [-pi, pi].
double heading(const RigidTransform& world_from_base);

// Wraps an angle to (-pi, pi].
double wrap_angle(double radians);

// How many of the six pose parameters are estimated (robot.dof).
enum class Dof { planar3 = 3, height4 = 4, full6 = 6 };

}  // namespace irloc
