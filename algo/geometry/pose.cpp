#include "algo/geometry/pose.hpp"

#include <cmath>
#include <numbers>

namespace irloc {

Eigen::Matrix3d rotation_from_rpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

RollPitchYaw rpy_from_rotation(const Eigen::Matrix3d& r) {
  RollPitchYaw rpy;
  rpy.pitch = std::atan2(-r(2, 0), std::hypot(r(0, 0), r(1, 0)));
  rpy.yaw = wrap_angle(std::atan2(r(1, 0), r(0, 0)));
  rpy.roll = wrap_angle(std::atan2(r(2, 1), r(2, 2)));
  return rpy;
}

double wrap_angle(double radians) {
  constexpr double pi = std::numbers::pi;
  double wrapped = std::remainder(radians, 2 * pi);  // in [-pi, pi]
  if (wrapped <= -pi) wrapped += 2 * pi;
  return wrapped;
}

double heading(const RigidTransform& world_from_base) {
  return std::atan2(world_from_base.rotation(1, 0), world_from_base.rotation(0, 0));
}

}  // namespace irloc
