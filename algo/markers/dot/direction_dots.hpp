#pragma once
// Stage 3: the direction dots O, X, Y of one group, as in the paper: the farthest pair are X and
// Y (the diagonal of the grid; cell (3, 3) is never populated, so no other pair is as far), O is
// the dot farthest from their midpoint, and the sign of the cross product OX x OY tells X from Y.
// The triangle must be right and isosceles at O and of the expected size; when it is not, the
// farthest dot is taken for a stray blob and set aside, a few times at most.

#include <cstdint>

#include "algo/markers/dot/dot_candidates.hpp"
#include "algo/markers/dot/dot_grouping.hpp"
#include "algo/markers/dot/dot_source_config.hpp"

namespace irloc::dot {

struct DirectionDots {
  std::uint8_t o = 0, x = 0, y = 0;  // candidate indices
  double side_ratio_error = 0;       // | |OX| / |OY| - 1 |
  double right_angle_error = 0;      // | angle XOY - pi/2 |, radians
  double scale = 0;                  // |XY| / expected |XY|
};

// expected_diagonal: |XY| in the nominal plane, metres (3 sqrt(2) pitch). true: the triangle is
// found, and the stray members dropped on the way are removed from group. false when no right
// isosceles triangle of plausible size is found; group is then left whole.
bool find_direction_dots(const DotCandidateList& candidates, const DotSourceConfig& config, double expected_diagonal,
                         DotGroup& group, DirectionDots& found);

}  // namespace irloc::dot
