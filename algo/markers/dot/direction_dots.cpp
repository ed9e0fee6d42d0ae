#include "algo/markers/dot/direction_dots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <span>

namespace irloc::dot {
namespace {

constexpr int kMaxStraysRemoved = 4;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A member set aside as a stray: where it was in the group, and which candidate.
struct SetAside {
  std::size_t position = 0;
  std::uint8_t member = 0;
};

SetAside remove_member(DotGroup& group, std::size_t position) {
  const SetAside removed{position, group.members[position]};
  for (std::size_t k = position; k + 1 < group.members.size(); ++k) group.members[k] = group.members[k + 1];
  group.members.pop_back();
  return removed;
}

// Puts the members set aside back where they were, the last removed first: the group as it came.
void restore_members(std::span<const SetAside> set_aside, DotGroup& group) {
  for (auto it = set_aside.rbegin(); it != set_aside.rend(); ++it) {
    group.members.push_back(0);
    for (std::size_t k = group.members.size() - 1; k > it->position; --k) group.members[k] = group.members[k - 1];
    group.members[it->position] = it->member;
  }
}

// The direction dots' triangle as the group suggests it: the farthest pair (a, b: the ends of the
// X-Y diagonal) and the member farthest from the pair's midpoint (o).
struct DiagonalTriangle {
  std::size_t a = 0, b = 1, o = 0;
  double diagonal = 0;  // |a - b| in the plane
};

DiagonalTriangle diagonal_triangle(const DotCandidateList& candidates, const DotGroup& group) {
  const auto plane = [&](std::size_t member) -> const Eigen::Vector2d& {
    return candidates[group.members[member]].plane;
  };
  const std::size_t n = group.members.size();
  DiagonalTriangle triangle;
  triangle.o = n;
  double farthest = -1;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
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
    if (k == triangle.a || k == triangle.b) continue;
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
  std::array<SetAside, kMaxStraysRemoved + 1> set_aside;
  std::size_t set_aside_count = 0;
  for (int attempt = 0; attempt <= kMaxStraysRemoved && group.members.size() >= 3; ++attempt) {
    const std::size_t n = group.members.size();
    const DiagonalTriangle triangle = diagonal_triangle(candidates, group);
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
      return true;
    }
    // The farthest pair holds a stray when the triangle is wrong: drop whichever of the pair lies
    // farther from the group's centroid.
    Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < n; ++k) centroid += plane(k);
    centroid /= static_cast<double>(n);
    set_aside[set_aside_count++] =
        remove_member(group, (plane(a) - centroid).squaredNorm() > (plane(b) - centroid).squaredNorm() ? a : b);
  }
  restore_members({set_aside.data(), set_aside_count}, group);
  return false;
}

}  // namespace irloc::dot
