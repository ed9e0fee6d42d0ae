#pragma once
// Which side of a refined square is the solid one, by the dash patterns read along its four sides
// (dash_pattern.hpp) under one of the map's patterns.

#include <array>

#include "algo/markers/square/dash_pattern.hpp"
#include "algo/markers/square/square_config.hpp"

namespace irloc::square {

// How much of the square was seen: the smallest visible fraction of its four sides (the
// confidence before the fit's quality scales it).
double seen_fraction(const std::array<DashPattern, 4>& patterns);

// The solid side by the whole dash model, or -1 when not exactly one side reads solid and at
// least two others dashed (the fourth, crossed by clutter or mostly hidden, may read neither, but
// not solid). The solid side shows at most solid_max_gap_rate gaps per dash period, is
// covered along at least solid_min_fill of its visible length and keeps no dash phase; a dashed
// side shows at least dashed_min_gap_rate gaps per period and keeps the pattern's phase read from
// its start corner (forward: side k starts at corner k - 1) by at least min_dash_coherence. Far
// solid tape seen by few pixels has sampling holes that read as a few gaps, but no phase; a
// strip of clutter read as a side keeps no phase either. out_of_phase: the gaps alone would have
// classified the sides, the phases did not agree.
int solid_side_of(const std::array<DashPattern, 4>& patterns, bool forward, const SquareConfig& config,
                  bool& out_of_phase);

}  // namespace irloc::square
