#pragma once
// Layouts of the square-path scenes shared by the tests and the goal benchmark: random clutter
// around a square, and the map of four squares of two dash patterns.

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "algo/map/marker_map.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {

// Random clutter near the sides of `square` (strips of 0.4-2.4 m, 3-8 cm wide, most parallel to
// the nearest side, 8-43 cm outside or inside it; crescents of 5-15 cm radius facing anywhere):
// 2 to 4 things per scene.
inline std::vector<Clutter> random_clutter(std::mt19937& rng, const SquareMarker& square = tape_square(0, 0, 0)) {
  const Eigen::Vector2d c0 = square.corners[0].head<2>(), c1 = square.corners[1].head<2>();
  const Eigen::Vector2d centre = (c0 + square.corners[2].head<2>()) / 2;
  const double square_yaw = std::atan2(c1.y() - c0.y(), c1.x() - c0.x());
  const double half = (c1 - c0).norm() / 2;
  const Eigen::Rotation2Dd turn(square_yaw);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::vector<Clutter> clutter(2 + static_cast<std::size_t>(3 * uniform(rng)));
  for (Clutter& item : clutter) {
    const double side = std::floor(4 * uniform(rng)) * std::numbers::pi / 2;  // direction of the side
    const Eigen::Vector2d along(std::cos(side), std::sin(side)), outward(along.y(), -along.x());
    const double offset = (uniform(rng) < 0.75 ? 1 : -1) * (0.08 + 0.35 * uniform(rng));
    item.centre = centre + turn * (outward * (half + offset) + along * (1.6 * uniform(rng) - 0.8) * half);
    if (uniform(rng) < 0.6) {
      item.kind = Clutter::Kind::strip;
      item.yaw = square_yaw + (uniform(rng) < 0.7 ? side : side + (uniform(rng) - 0.5) * std::numbers::pi);
      item.length = 0.4 + 2.0 * uniform(rng);
      item.width = 0.03 + 0.05 * uniform(rng);
    } else {
      item.kind = Clutter::Kind::crescent;
      item.yaw = 2 * std::numbers::pi * uniform(rng);
      item.width = 0.05 + 0.1 * uniform(rng);
    }
  }
  return clutter;
}

inline SquareMarker patterned(SquareMarker marker, std::string name, double dash, double gap) {
  marker.name = std::move(name);
  marker.dash = dash;
  marker.gap = gap;
  return marker;
}

// Four squares 6 m apart: two of the default pattern (0.10 / 0.10), two of a longer one
// (0.20 / 0.10: 1.5 times the period).
inline std::vector<SquareMarker> map_of_four() {
  return {patterned(tape_square(0, 0, 0), "a1", 0.10, 0.10), patterned(tape_square(6, 0, 0.3), "b1", 0.20, 0.10),
          patterned(tape_square(0, 6, 1.0), "a2", 0.10, 0.10), patterned(tape_square(6, 6, -0.5), "b2", 0.20, 0.10)};
}

}  // namespace irloc::test
