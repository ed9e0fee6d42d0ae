#include "algo/markers/dot/nominal_plane.hpp"

#include <Eigen/Geometry>

namespace irloc::dot {
namespace {

// Rays closer than this to the plane (cosine of the angle to its normal) are not used: their
// intersection is too far and too sensitive.
constexpr double kMinCosine = 0.05;

}  // namespace

NominalPlane::NominalPlane(const Eigen::Vector3d& up_c, double distance)
    : normal_(up_c.normalized()), distance_(distance) {
  // Camera x projected into the plane; camera y when x is (nearly) the normal itself.
  Eigen::Vector3d seed = Eigen::Vector3d::UnitX() - normal_.x() * normal_;
  if (seed.norm() < 1e-6) seed = Eigen::Vector3d::UnitY() - normal_.y() * normal_;
  e1_ = seed.normalized();
  e2_ = normal_.cross(e1_);
}

bool NominalPlane::intersect(const Eigen::Vector3d& bearing, Eigen::Vector2d& plane_xy) const {
  const double along_normal = bearing.dot(normal_);
  if (along_normal < kMinCosine * bearing.norm()) return false;
  const Eigen::Vector3d point_c = bearing * (distance_ / along_normal);
  plane_xy = {point_c.dot(e1_), point_c.dot(e2_)};
  return true;
}

Eigen::Vector3d NominalPlane::point(const Eigen::Vector2d& plane_xy) const {
  return distance_ * normal_ + plane_xy.x() * e1_ + plane_xy.y() * e2_;
}

}  // namespace irloc::dot
