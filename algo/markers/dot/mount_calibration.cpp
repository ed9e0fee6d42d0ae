#include "algo/markers/dot/mount_calibration.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "algo/geometry/pose.hpp"

namespace irloc::dot {
namespace {

// The yaw range the poses cover, unwrapped step by step, rad.
double turned_range(std::span<const PlanarPose> poses) {
  double unwrapped = poses[0].yaw, low = unwrapped, high = unwrapped;
  for (std::size_t k = 1; k < poses.size(); ++k) {
    unwrapped += wrap_angle(poses[k].yaw - poses[k - 1].yaw);
    low = std::min(low, unwrapped);
    high = std::max(high, unwrapped);
  }
  return high - low;
}

// The circle through the positions: Kasa's algebraic fit, then Gauss-Newton on the geometric
// distances. False when the algebraic fit has no real radius.
bool fit_circle(std::span<const PlanarPose> poses, Eigen::Vector2d& centre, double& radius) {
  // Kasa: x^2 + y^2 + D x + E y + F = 0 in the least-squares sense.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const PlanarPose& p : poses) {
    const Eigen::Vector3d row(p.x, p.y, 1.0);
    normal += row * row.transpose();
    rhs += row * -(p.x * p.x + p.y * p.y);
  }
  const Eigen::Vector3d def = normal.ldlt().solve(rhs);
  centre = Eigen::Vector2d(-def(0) / 2, -def(1) / 2);
  radius = std::sqrt(std::max(0.0, centre.squaredNorm() - def(2)));
  if (!std::isfinite(radius)) return false;

  // Gauss-Newton on r_k = |p_k - c| - R.
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (const PlanarPose& p : poses) {
      const Eigen::Vector2d d = Eigen::Vector2d(p.x, p.y) - centre;
      const double distance = d.norm();
      if (distance < 1e-12) continue;
      const Eigen::Vector3d j(-d.x() / distance, -d.y() / distance, -1.0);
      const double r = distance - radius;
      jtj += j * j.transpose();
      jtr += j * r;
    }
    const Eigen::Vector3d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) break;
    centre += step.head<2>();
    radius += step(2);
    if (step.norm() < 1e-12) break;
  }
  return true;
}

}  // namespace

MountOffsetFit fit_mount_offset(std::span<const PlanarPose> poses, double min_turn) {
  MountOffsetFit fit;
  if (poses.size() < 8) return fit;
  fit.turned = turned_range(poses);
  if (fit.turned < min_turn) return fit;
  Eigen::Vector2d centre;
  double radius = 0;
  if (!fit_circle(poses, centre, radius)) return fit;

  double squared = 0;
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  for (const PlanarPose& p : poses) {
    const Eigen::Vector2d d = Eigen::Vector2d(p.x, p.y) - centre;
    squared += std::pow(d.norm() - radius, 2);
    const double c = std::cos(p.yaw), s = std::sin(p.yaw);
    offset += Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y());  // R(yaw)^T d
  }
  fit.centre = centre;
  fit.radius = std::abs(radius);
  fit.offset = offset / static_cast<double>(poses.size());
  fit.circle_rms = std::sqrt(squared / static_cast<double>(poses.size()));
  fit.ok = fit.offset.allFinite();
  return fit;
}

}  // namespace irloc::dot
