#pragma once
// Where a ray enters a person: people are vertical cylinders standing on the floor (z = 0).
// Shared by the renderer and the occlusion truth of the metrics.

#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace irloc::sim {

// Entry distance of the ray c + t d (t > 0) into the vertical cylinder of `radius` and `height`
// standing at `centre`, or infinity when it misses or starts inside (the camera inside a person:
// the person is not where the robot is).
inline double hit_cylinder(const Eigen::Vector3d& c, const Eigen::Vector3d& d, const Eigen::Vector2d& centre, double radius,
                           double height) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double ox = c.x() - centre.x(), oy = c.y() - centre.y();
  const double a = d.x() * d.x() + d.y() * d.y();
  if (a < 1e-12) return kInfinity;
  const double b = ox * d.x() + oy * d.y();
  const double k = ox * ox + oy * oy - radius * radius;
  if (k <= 0) return kInfinity;
  const double discriminant = b * b - a * k;
  if (discriminant < 0) return kInfinity;
  const double t = (-b - std::sqrt(discriminant)) / a;
  if (t <= 0) return kInfinity;
  const double z = c.z() + t * d.z();
  return z >= 0 && z <= height ? t : kInfinity;
}

}  // namespace irloc::sim
