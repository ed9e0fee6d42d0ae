#include "algo/markers/square/square_map_checks.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace irloc::square {

double mean_side(const SquareMarker& marker) {
  double sum = 0;
  for (std::size_t k = 0; k < 4; ++k) sum += (marker.corners[(k + 1) % 4] - marker.corners[k]).norm();
  return sum / 4;
}

double ceiling_z_of(const SquareMarker& marker) {
  double sum = 0;
  for (const Eigen::Vector3d& corner : marker.corners) sum += corner.z() / 4;
  return sum;
}

namespace {

// A level square, or std::invalid_argument naming the marker.
void check_square(const SquareMarker& marker) {
  const std::string name = "square marker '" + marker.name + "': ";
  const double side = mean_side(marker);
  const double z = ceiling_z_of(marker);
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector3d& a = marker.corners[k];
    const Eigen::Vector3d& b = marker.corners[(k + 1) % 4];
    const Eigen::Vector3d& c = marker.corners[(k + 2) % 4];
    if (std::abs(a.z() - z) > 0.01) throw std::invalid_argument(name + "corners are not level (z within 0.01 m)");
    if (std::abs((b - a).norm() - side) > 0.01 * side || std::abs((b - a).normalized().dot((c - b).normalized())) > 0.01) {
      throw std::invalid_argument(name + "corners are not a square (sides within 1 %, right angles)");
    }
  }
  if (side < 0.2) throw std::invalid_argument(name + "sides shorter than 0.2 m");
}

}  // namespace

std::vector<SquareMarker> checked_square_markers(std::span<const SquareMarker> markers) {
  if (markers.empty()) throw std::invalid_argument("square path: the map has no square marker");
  const SquareMarker& first = markers.front();
  for (const SquareMarker& marker : markers) {
    check_square(marker);
    const std::string names = "square markers '" + first.name + "' and '" + marker.name + "': ";
    if (std::abs(mean_side(marker) - mean_side(first)) > 0.01 * mean_side(first)) {
      throw std::invalid_argument(names + "sides differ (the squares of one map share their side within 1 %)");
    }
    if (marker.tape_width != first.tape_width) throw std::invalid_argument(names + "tape widths differ");
    if (std::abs(ceiling_z_of(marker) - ceiling_z_of(first)) > 0.01) {
      throw std::invalid_argument(names + "ceiling heights differ (within 0.01 m)");
    }
    for (const SquareMarker& other : markers) {
      const bool same_pattern = marker.dash == other.dash && marker.gap == other.gap;
      const double ratio = (marker.dash + marker.gap) / (other.dash + other.gap);
      if (!same_pattern && std::max(ratio, 1 / ratio) < kMinDashPeriodRatio - 1e-9) {
        throw std::invalid_argument("square markers '" + marker.name + "' and '" + other.name +
                                    "': dash patterns too alike to tell apart (equal, or dash + gap at least 1.5 times "
                                    "the other's)");
      }
    }
  }
  return {markers.begin(), markers.end()};
}

double ceiling_above_camera(const SquareMarker& marker, const RigidTransform& base_from_camera) {
  const double height = ceiling_z_of(marker) - base_from_camera.translation.z();
  if (!(height > 0.1)) throw std::invalid_argument("square marker '" + marker.name + "': not above the camera");
  return height;
}

}  // namespace irloc::square
