#include "algo/markers/dot/dot_marker_layout.hpp"

#include <cmath>

namespace irloc::dot {

Eigen::Vector3d cell_in_world(const DotMarker& marker, int cell) {
  return grid_in_world(marker, Eigen::Vector2d(cell_column(cell), cell_row(cell)));
}

Eigen::Vector3d grid_in_world(const DotMarker& marker, const Eigen::Vector2d& grid) {
  const Eigen::Vector3d x_axis(std::cos(marker.yaw), std::sin(marker.yaw), 0.0);
  const Eigen::Vector3d y_axis(std::sin(marker.yaw), -std::cos(marker.yaw), 0.0);
  return marker.origin + marker.pitch * (grid.x() * x_axis + grid.y() * y_axis);
}

}  // namespace irloc::dot
