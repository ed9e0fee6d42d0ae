#include "algo/markers/dot/direction_dots.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

namespace irloc::dot {
namespace {

constexpr int kMaxStraysRemoved = 4;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The group's members still taken for the marker's: bit k stands for group.members[k].
using KeptMembers = std::uint32_t;
static_assert(kMaxGroupSize < 32, "every member's bit must fit in KeptMembers");

bool is_kept(KeptMembers kept, std::size_t member) { return ((kept >> member) & 1U) != 0; }

// Removes the members not kept, in order.
void keep_only(KeptMembers kept, DotGroup& group) {
  std::size_t to = 0;
  for (std::size_t k = 0; k < group.members.size(); ++k) {
    if (is_kept(kept, k)) group.members[to++] = group.members[k];
  }
  while (group.members.size() > to) group.members.pop_back();
}

// The direction dots' triangle as the kept members suggest it: the farthest pair (a, b: the ends
// of the X-Y diagonal) and the member farthest from the pair's midpoint (o).
struct DiagonalTriangle {
  std::size_t a = 0, b = 1, o = 0;
  double diagonal = 0;  // |a - b| in the plane
};

DiagonalTriangle diagonal_triangle(const DotCandidateList& candidates, const DotGroup& group, KeptMembers kept) {
  const auto plane = [&](std::size_t member) -> const Eigen::Vector2d& {
    return candidates[group.members[member]].plane;
  };
  const std::size_t n = group.members.size();
  DiagonalTriangle triangle;
  triangle.o = n;
  double farthest = -1;
  for (std::size_t i = 0; i < n; ++i) {
    if (!is_kept(kept, i)) continue;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!is_kept(kept, j)) continue;
      const double d = (plane(i) - plane(j)).squaredNorm();
      if (d > farthest) {
        farthest = d;
        triangle.a = i;
        triangle.b = j;
      }
    }
  }
  const Eigen::Vector2d midpoint = 0.5 * (plane(triangle.a) + plane(triangle.b));
  double o_distance = -1;
  for (std::size_t k = 0; k < n; ++k) {
    if (!is_kept(kept, k) || k == triangle.a || k == triangle.b) continue;
    const double d = (plane(k) - midpoint).squaredNorm();
    if (d > o_distance) {
      o_distance = d;
      triangle.o = k;
    }
  }
  triangle.diagonal = std::sqrt(farthest);
  return triangle;
}

}  // namespace

bool find_direction_dots(const DotCandidateList& candidates, const DotSourceConfig& config, double expected_diagonal,
                         DotGroup& group, DirectionDots& found) {
  const auto plane = [&](std::size_t member) -> const Eigen::Vector2d& {
    return candidates[group.members[member]].plane;
  };
  const std::size_t size = group.members.size();
  KeptMembers kept = (KeptMembers{1} << size) - 1;
  for (int attempt = 0; attempt <= kMaxStraysRemoved && std::popcount(kept) >= 3; ++attempt) {
    const DiagonalTriangle triangle = diagonal_triangle(candidates, group, kept);
    const std::size_t a = triangle.a, b = triangle.b, o = triangle.o;
    const Eigen::Vector2d to_a = plane(a) - plane(o);
    const Eigen::Vector2d to_b = plane(b) - plane(o);
    const double side_a = to_a.norm();
    const double side_b = to_b.norm();
    const double scale = triangle.diagonal / expected_diagonal;
    const double side_ratio_error = std::abs(side_a / side_b - 1.0);
    const double angle = std::acos(std::clamp(to_a.dot(to_b) / (side_a * side_b), -1.0, 1.0));
    const double right_angle_error = std::abs(angle - std::numbers::pi / 2);
    const bool plausible = scale >= 1.0 / config.scale_tolerance && scale <= config.scale_tolerance &&
                           side_ratio_error <= config.max_side_ratio_error &&
                           right_angle_error <= config.max_right_angle_error;
    if (plausible) {
      // Seen from below (the camera's side) a marker's OX x OY is negative in the plane's
      // right-handed basis, whose normal points up, away from the camera.
      const bool a_is_x = cross(to_a, to_b) < 0;
      found.o = group.members[o];
      found.x = group.members[a_is_x ? a : b];
      found.y = group.members[a_is_x ? b : a];
      found.side_ratio_error = side_ratio_error;
      found.right_angle_error = right_angle_error;
      found.scale = scale;
      keep_only(kept, group);
      return true;
    }
    // The farthest pair holds a stray when the triangle is wrong: drop whichever of the pair lies
    // farther from the centroid of the kept members.
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < size; ++k) {
      if (is_kept(kept, k)) centroid += plane(k);
    }
    centroid /= static_cast<double>(std::popcount(kept));
    kept &= ~(KeptMembers{1} << ((plane(a) - centroid).squaredNorm() > (plane(b) - centroid).squaredNorm() ? a : b));
  }
  return false;
}

}  // namespace irloc::dot
