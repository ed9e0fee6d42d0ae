#pragma once
// Solid or dashed: the gaps along a side. Tape points are binned along the side; an empty
// stretch up to a gap long (plus blur) is a gap, a longer one is taken as hidden (a person, the
// edge of the view), not as evidence, so a half-hidden solid side still reads as solid. A dashed
// side shows about one gap per dash period of its visible length (gap_rate ~ 1), the solid side
// none (gap_rate ~ 0) and is covered all along (fill ~ 1). The fill of a dashed side depends on
// how the bins fall on the dash edges (0.5 to 0.75 for a = g), so the gaps are the better witness.

#include <span>

#include <Eigen/Core>


namespace irloc {

struct DashPattern {
  double visible_fraction = 0;  // of the side between the corner patches
  double fill = 0;              // of the visible length
  double gap_rate = 0;          // gaps per dash period (dash + gap) of the visible length
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

// How well the tape points along a dashed side, measured from its start corner (markers.md: tape
// iff s mod (a + g) < a), keep the phase of this pattern: the mean of cos(2 pi (s - a/2) / (a + g))
// over the points (corner patches left out). About sin(pi q) / (pi q), q = a / (a + g), for the
// side's own pattern (0.64 for a = g), near 0 for a pattern of another period or a solid side,
// negative when the side is read from its other end. The period identifies a square; a count of
// gaps does not on far, coarsely sampled tape.
double dash_coherence(std::span<const Eigen::Vector2d> points, const Eigen::Vector2d& start, const Eigen::Vector2d& end,
                      const DashGeometry& geometry);

}  // namespace irloc
