#pragma once
// The ceiling as the camera expects it: a plane at a known distance, facing the camera. Rays
// meeting it give each dot metric 2-D coordinates in which marker pitch and shape can be tested
// before any pose is known, whatever the lens (the rays come from the calibrated camera model).

#include <Eigen/Core>

namespace irloc::dot {

class NominalPlane {
 public:
  NominalPlane() = default;
  // up_c: the ceiling normal pointing away from the camera (toward the ceiling), camera frame,
  // any length. distance: metres from the camera centre to the plane along it.
  NominalPlane(const Eigen::Vector3d& up_c, double distance);

  // Where the ray along bearing (camera frame) meets the plane, in the plane's 2-D basis
  // (metres). false for rays that do not reach it (parallel or pointing away).
  bool intersect(const Eigen::Vector3d& bearing, Eigen::Vector2d& plane_xy) const;
  // The camera-frame point of plane coordinates.
  Eigen::Vector3d point(const Eigen::Vector2d& plane_xy) const;

  double distance() const { return distance_; }

 private:
  Eigen::Vector3d normal_ = Eigen::Vector3d::UnitZ();
  // Right-handed basis (e1, e2, normal); for an upward camera e1 = camera x, e2 = camera y.
  Eigen::Vector3d e1_ = Eigen::Vector3d::UnitX();
  Eigen::Vector3d e2_ = Eigen::Vector3d::UnitY();
  double distance_ = 1;
};

}  // namespace irloc::dot
