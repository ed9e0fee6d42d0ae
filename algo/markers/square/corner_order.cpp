#include "algo/markers/square/corner_order.hpp"

namespace irloc::square {

std::array<Eigen::Vector2d, 4> order_corners(const std::array<Eigen::Vector2d, 4>& measured, int solid_side,
                                             double map_turn) {
  const auto at = [&](int k) { return measured[static_cast<std::size_t>((k % 4 + 4) % 4)]; };
  // Forward: c0 = start of the solid side, then around in the measured order.
  std::array<Eigen::Vector2d, 4> forward{at(solid_side - 1), at(solid_side), at(solid_side + 1), at(solid_side + 2)};
  if ((turn(forward[0], forward[1], forward[2]) > 0) == (map_turn > 0)) return forward;
  // Backward: c0 = end of the solid side, then around against the measured order.
  return {at(solid_side), at(solid_side - 1), at(solid_side - 2), at(solid_side - 3)};
}

}  // namespace irloc::square
