#include "algo/survey/ceiling_pose.hpp"

#include <cmath>

#include "algo/geometry/pose.hpp"

namespace irloc::survey {

CeilingPose relative_pose(const CeilingPose& a, const CeilingPose& b, CeilingJacobian* d_a, CeilingJacobian* d_b) {
  const double c = std::cos(a[3]), s = std::sin(a[3]);
  const double dx = b[0] - a[0], dy = b[1] - a[1];
  CeilingPose relative;
  relative << c * dx + s * dy, -s * dx + c * dy, b[2] - a[2], wrap_angle(b[3] - a[3]);
  if (d_b != nullptr) {
    *d_b << c, s, 0, 0,  //
        -s, c, 0, 0,     //
        0, 0, 1, 0,      //
        0, 0, 0, 1;
  }
  if (d_a != nullptr) {
    *d_a << -c, -s, 0, -s * dx + c * dy,  //
        s, -c, 0, -c * dx - s * dy,       //
        0, 0, -1, 0,                      //
        0, 0, 0, -1;
  }
  return relative;
}

CeilingPose compose(const CeilingPose& a, const CeilingPose& a_to_b) {
  const double c = std::cos(a[3]), s = std::sin(a[3]);
  CeilingPose b;
  b << a[0] + c * a_to_b[0] - s * a_to_b[1], a[1] + s * a_to_b[0] + c * a_to_b[1], a[2] + a_to_b[2],
      wrap_angle(a[3] + a_to_b[3]);
  return b;
}

CeilingPose pose_difference(const CeilingPose& b, const CeilingPose& a) {
  CeilingPose difference = b - a;
  difference[3] = wrap_angle(difference[3]);
  return difference;
}

RigidTransform to_transform(const CeilingPose& pose) {
  return {rotation_from_rpy(0, 0, pose[3]), pose.head<3>()};
}

CeilingPose ceiling_pose_from(const RigidTransform& transform) {
  const Eigen::Vector3d& t = transform.translation;
  return {t.x(), t.y(), t.z(), heading(transform)};
}

}  // namespace irloc::survey
