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

namespace irloc::square {

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
  // The camera's height below the square is known (dof 3): a side lies d from its opposite on the
  // ceiling plane (find_level_square_candidates also tries the cell there).
  bool exact_side = false;
};

inline constexpr std::size_t kMaxSquareCandidates = 8;
using SquareCandidates = StaticVector<SquareSides, kMaxSquareCandidates>;

// peaks: in plane units (kPlaneUnitsPerMetre). found: the kMaxSquareCandidates sets with the most
// votes, most first; empty when no four peaks form such a square.
void find_square_candidates(const HoughLineList& peaks, const SquareSearchParams& params, SquareCandidates& found);

// A level camera (dof 3 or 4) sees the square as a square on the ceiling plane: its sides meet at
// right angles to within the Hough bins. The sides are searched in the accumulator itself, not
// among its peaks: the peaks' non-maximum suppression (+-3 degrees) lets a strong strip of tape a
// few rho bins beside a side hide that side, and a few strong lines' side lobes fill the peak list
// before a far, thinly sampled side gets in. For each orientation of the strongest peaks (modulo a
// right angle, each bin its own; at most kMaxSquareOrientations), the two columns theta and
// theta + 90 degrees give their kMaxLinesPerFamily strongest rho maxima; every two of one column d
// apart (within side_tolerance) and two of the other form a hypothesis. found: as above, the
// strongest kMaxSquareCandidates, each set of four lines once.
inline constexpr std::size_t kMaxSquareOrientations = 6;
inline constexpr std::size_t kMaxLinesPerFamily = 8;
void find_level_square_candidates(const HoughLines& hough, const HoughLineList& peaks, const SquareSearchParams& params,
                                  SquareCandidates& found);

}  // namespace irloc::square
