#pragma once
// The search over Hough peaks for the four sides of a square of side d (the paper's step): two
// pairs of parallel lines, each pair d apart, the pairs perpendicular, within the configured
// tolerances. Every such set is a hypothesis; the strongest few by votes are kept, and the
// detector scores each against the whole tape model (square_detector.hpp): a stray strip of tape
// near the square can outvote a dashed side, so the most votes alone do not decide. (The paper
// takes the strongest peak as the solid side; with half of the solid side hidden a dashed side
// can outvote it, so here the sides are found first and told apart by their dash pattern.)

#include <array>
#include <cstdint>

#include "algo/core/static_vector.hpp"
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

inline constexpr std::size_t kMaxSquareCandidates = 8;
using SquareCandidates = StaticVector<SquareSides, kMaxSquareCandidates>;

// peaks: in plane units (kPlaneUnitsPerMetre). found: the kMaxSquareCandidates sets with the most
// votes, most first; empty when no four peaks form such a square.
void find_square_candidates(const HoughLineList& peaks, const SquareSearchParams& params, SquareCandidates& found);

}  // namespace irloc
