#include "algo/markers/square/solid_side.hpp"

#include <algorithm>

namespace irloc::square {

double seen_fraction(const std::array<DashPattern, 4>& patterns) {
  double smallest = 1;
  for (const DashPattern& pattern : patterns) smallest = std::min(smallest, pattern.visible_fraction);
  return smallest;
}

int solid_side_of(const std::array<DashPattern, 4>& patterns, bool forward, const SquareConfig& config,
                  bool& out_of_phase) {
  int solid = -1, by_gaps = -1;
  int dashed = 0, dashed_by_gaps = 0;
  for (int k = 0; k < 4; ++k) {
    const DashPattern& pattern = patterns[static_cast<std::size_t>(k)];
    const double phase = forward ? pattern.phase_from_start : pattern.phase_from_end;
    if (pattern.gap_rate <= config.solid_max_gap_rate && pattern.fill >= config.solid_min_fill) {
      by_gaps = by_gaps < 0 ? k : 4;  // 4: a second solid side
      if (phase < config.min_dash_coherence) solid = solid < 0 ? k : 4;
    } else if (pattern.gap_rate >= config.dashed_min_gap_rate) {
      ++dashed_by_gaps;
      if (phase >= config.min_dash_coherence) ++dashed;
    }
  }
  if (dashed >= 2 && solid >= 0 && solid < 4 && by_gaps == solid) return solid;
  out_of_phase = dashed_by_gaps == 3 && by_gaps >= 0 && by_gaps < 4;
  return -1;
}

}  // namespace irloc::square
