#include "algo/markers/square/tape_levelling.hpp"

#include <cmath>

namespace irloc::square {

LevelledTape::LevelledTape(double ceiling_above_camera, std::size_t capacity)
    : ceiling_above_camera_(ceiling_above_camera), points_(capacity) {}

bool LevelledTape::levelled_near(const RollPitchYaw& tilt) const {
  return levelled_ &&
         !(std::abs(tilt.roll - tilt_.roll) > kTiltAgreement || std::abs(tilt.pitch - tilt_.pitch) > kTiltAgreement);
}

void LevelledTape::level(const RollPitchYaw& tilt, std::span<const Eigen::Vector2d> points) {
  tilt_ = tilt;
  level_from_base_ = rotation_from_rpy(tilt.roll, tilt.pitch, 0);
  for (std::size_t k = 0; k < points.size(); ++k) points_[k] = levelled(points[k]);
  count_ = points.size();
  levelled_ = true;
}

Eigen::Vector2d LevelledTape::levelled(const Eigen::Vector2d& point) const {
  const double h0 = ceiling_above_camera_;
  const Eigen::Vector3d ray = level_from_base_ * Eigen::Vector3d(point.x(), point.y(), h0);
  return ray.head<2>() * (h0 / ray.z());
}

std::array<Eigen::Vector2d, 4> LevelledTape::levelled(const std::array<Eigen::Vector2d, 4>& corners) const {
  std::array<Eigen::Vector2d, 4> level;
  for (std::size_t k = 0; k < 4; ++k) level[k] = levelled(corners[k]);
  return level;
}

}  // namespace irloc::square
