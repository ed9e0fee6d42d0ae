#include "algo/pipeline/pose_fusion.hpp"

#include <algorithm>
#include <cmath>

#include "algo/geometry/pose.hpp"

namespace irloc {

bool fuse_level_poses(const LevelPose& a, const LevelPose& b, const FusionGate& gate, LevelPose& fused) {
  if (!(a.position_sigma > 0 && b.position_sigma > 0 && a.yaw_sigma > 0 && b.yaw_sigma > 0)) return false;
  const double yaw_difference = wrap_angle(b.yaw - a.yaw);
  if (std::hypot(b.x - a.x, b.y - a.y) > gate.position || std::abs(yaw_difference) > gate.yaw) return false;
  const double wa = 1 / (a.position_sigma * a.position_sigma);
  const double wb = 1 / (b.position_sigma * b.position_sigma);
  const double share_b = wb / (wa + wb);
  fused.x = a.x + share_b * (b.x - a.x);
  fused.y = a.y + share_b * (b.y - a.y);
  fused.z = a.z + share_b * (b.z - a.z);
  fused.position_sigma = 1 / std::sqrt(wa + wb);
  const double ya = 1 / (a.yaw_sigma * a.yaw_sigma);
  const double yb = 1 / (b.yaw_sigma * b.yaw_sigma);
  fused.yaw = wrap_angle(a.yaw + yb / (ya + yb) * yaw_difference);
  fused.yaw_sigma = 1 / std::sqrt(ya + yb);
  return true;
}

void point_fit_uncertainty(std::span<const double> footprints, std::span<const Eigen::Vector2d> world_points,
                           double sigma_px, LevelPose& pose) {
  const std::size_t n = std::min(footprints.size(), world_points.size());
  if (n == 0) {
    pose.position_sigma = pose.yaw_sigma = 0;
    return;
  }
  double footprint = 0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    footprint += footprints[i] / static_cast<double>(n);
    centroid += world_points[i] / static_cast<double>(n);
  }
  double spread_squared = 0;
  for (std::size_t i = 0; i < n; ++i) spread_squared += (world_points[i] - centroid).squaredNorm() / static_cast<double>(n);
  const double point_sigma = sigma_px * footprint;
  pose.position_sigma = point_sigma / std::sqrt(static_cast<double>(n));
  // A rotation about the centroid moves each point by angle * distance: one point's error over the
  // lever arm, averaged over the points.
  pose.yaw_sigma = point_sigma / std::sqrt(std::max(spread_squared, 1e-6) * static_cast<double>(n));
}

}  // namespace irloc
