#pragma once
// Which measured corner is which map corner: the solid side is c0 -> c1, and the direction
// around the square is fixed by the cross-product test, since a level camera sees the ceiling
// unmirrored (the plane keeps the map's handedness).

#include <array>

#include <Eigen/Core>

namespace irloc::square {

// measured[k]: corner between sides k and k + 1 (side k runs from measured[k - 1] to
// measured[k]), in a frame with the map's handedness. solid_side: index of the solid side.
// map_turn: turn(c0, c1, c2) of the map's corners in W's x-y. Returns the measured corners as
// c0..c3.
std::array<Eigen::Vector2d, 4> order_corners(const std::array<Eigen::Vector2d, 4>& measured, int solid_side,
                                             double map_turn);

// z of (b - a) x (c - b).
inline double turn(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - b;
  return u.x() * v.y() - u.y() * v.x();
}

}  // namespace irloc::square
