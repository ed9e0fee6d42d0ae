#pragma once
// The search over Hough peaks for the four sides of a square of side d (the paper's step): two
// pairs of parallel lines, each pair d apart, the pairs perpendicular, within the configured
// tolerances. Of all such sets the one with the most votes wins. (The paper takes the strongest
// peak as the solid side; with half of the solid side hidden a dashed side can outvote it, so
// here the sides are found first and told apart afterwards by their dash pattern.)

#include <array>
#include <cstdint>

#include "algo/kernels/hough_lines.hpp"

namespace irloc {

// The line {p : p . (cos theta, sin theta) = rho} on the ceiling plane, metres.
struct PlaneLine {
  double theta = 0;
  double rho = 0;
  std::uint32_t votes = 0;
};

// sides[0] || sides[2], sides[1] || sides[3]; corner k is sides[k] meets sides[(k + 1) % 4].
struct SquareSides {
  std::array<PlaneLine, 4> sides;
  std::uint32_t votes = 0;
};

struct SquareSearchParams {
  double side = 2.0;                // d, metres
  double side_tolerance = 0.10;     // fraction of d
  double angle_tolerance = 0.1745;  // radians
};

// peaks: in plane units (kPlaneUnitsPerMetre). false when no four peaks form such a square.
bool find_square_sides(const HoughLineList& peaks, const SquareSearchParams& params, SquareSides& found);

}  // namespace irloc
