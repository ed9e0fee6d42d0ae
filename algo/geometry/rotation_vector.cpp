#include "algo/geometry/rotation_vector.hpp"

#include <Eigen/Geometry>

namespace irloc {

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Matrix3d exp_rotation(const Eigen::Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity() + skew(v);
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

Eigen::Vector3d log_rotation(const Eigen::Matrix3d& r) {
  const Eigen::AngleAxisd axis_angle(r);
  return axis_angle.angle() * axis_angle.axis();
}

}  // namespace irloc
