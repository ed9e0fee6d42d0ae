#pragma once
// Solid or dashed: the gaps along a side. Tape points are binned along the side; an empty
// stretch up to a gap long (plus blur) is a gap, a longer one is taken as hidden (a person, the
// edge of the view), not as evidence, so a half-hidden solid side still reads as solid. A dashed
// side shows about one gap per dash period of its visible length (gap_rate ~ 1), the solid side
// none (gap_rate ~ 0) and is covered all along (fill ~ 1). The fill of a dashed side depends on
// how the bins fall on the dash edges (0.5 to 0.75 for a = g), so the gaps are the better witness.

#include <span>

#include <Eigen/Core>


namespace irloc::square {

// The phase: how well the covered bins keep the pattern's dashes, read from one end of the side
// (markers.md: tape iff s mod (a + g) < a, s from the side's start corner): the mean of
// cos(2 pi (s - a/2) / (a + g)) over the tape points, each at its bin's centre (corner patches
// left out). About
// sin(pi q) / (pi q), q = a / (a + g), for a dashed side of this pattern read from its start corner
// (0.64 for a = g); near 0 for a solid side, whose sampling holes fall anywhere, and for a pattern
// of another period; negative for a dashed side read from its other end (when its length is a
// whole number of periods). The period identifies a square; a count of gaps does not on far,
// coarsely sampled tape.
struct DashPattern {
  double visible_fraction = 0;  // of the side between the corner patches
  double fill = 0;              // of the visible length
  double gap_rate = 0;          // gaps per dash period (dash + gap) of the visible length
  double phase_from_start = 0;  // the phase read from start
  double phase_from_end = 0;    // the phase read from end
};

struct DashGeometry {
  double tape_width = 0.05;
  double dash = 0.10;
  double gap = 0.10;
};

// The side from start to end (metres on the ceiling plane); points (metres) within tape_width of
// it count.
DashPattern measure_dash_pattern(std::span<const Eigen::Vector2d> points, const Eigen::Vector2d& start,
                                 const Eigen::Vector2d& end, const DashGeometry& geometry);

}  // namespace irloc::square
