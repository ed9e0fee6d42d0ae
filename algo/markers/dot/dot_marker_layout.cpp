#include "algo/markers/dot/dot_marker_layout.hpp"

#include <cmath>

namespace irloc::dot {

Eigen::Vector3d cell_in_world(const DotMarker& marker, int cell) {
  const Eigen::Vector3d x_axis(std::cos(marker.yaw), std::sin(marker.yaw), 0.0);
  const Eigen::Vector3d y_axis(std::sin(marker.yaw), -std::cos(marker.yaw), 0.0);
  const Eigen::Vector3d local = cell_in_marker(cell, marker.pitch);
  return marker.origin + local.x() * x_axis + local.y() * y_axis;
}

}  // namespace irloc::dot
