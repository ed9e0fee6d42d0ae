#pragma once
// Settings of the square tape marker path (config YAML section `square`, docs/square_markers.md).
// Lengths in metres, angles in radians, as everywhere in the config.

#include <cstdint>

namespace irloc::square {

struct SquareConfig {
  // Strobe difference above which a pixel is tape; 0 = from the pair's shared noise estimate
  // (algo/kernels/difference_noise.hpp): median + 5 sigma, at least 6.
  std::uint16_t threshold = 0;
  // Rays further than this from the vertical are not mapped to the ceiling: near the horizon a
  // pixel covers too much ceiling to be worth its vote.
  double max_ray_angle = 1.31;  // 75 degrees
  // Search tolerances of the paper: side length within +-side_tolerance * d, parallel and
  // perpendicular sides within +-angle_tolerance. Under dof 3 (the height known) the side length
  // is searched within at most max_side_error * d plus a tape width.
  double side_tolerance = 0.10;
  double angle_tolerance = 0.1745;  // 10 degrees
  // Under dof 6: a tilted camera skews the square on the level table (a 5 degree tilt stretches
  // a side 50 degrees off the axis by a quarter), so the search is wider; the 6-dof fit's checks
  // on the ceiling (max_corner_residual, max_side_error) stay as strict.
  double tilted_side_tolerance = 0.30;
  double tilted_angle_tolerance = 0.35;  // 20 degrees
  // Each side must be seen along at least this fraction of its length.
  double min_visible_fraction = 0.3;
  // Solid or dashed (dash_pattern.hpp): the solid side shows at most solid_max_gap_rate gaps per
  // dash period and is covered along at least solid_min_fill of its visible length; a dashed
  // side shows at least dashed_min_gap_rate gaps per period (about 1 when fully seen).
  double solid_min_fill = 0.8;
  double solid_max_gap_rate = 0.4;
  double dashed_min_gap_rate = 0.5;
  // Consistency checks before a pose is reported: RMS distance of the four measured corners from
  // the fitted map square, and each refined side length relative to the map's.
  double max_corner_residual = 0.02;
  double max_side_error = 0.03;
  // Of the square hypotheses that pass every check, the best (by confidence) is reported only if
  // its confidence is at least this many times that of the best one at another pose.
  double clear_win_ratio = 1.25;
  // Several squares in the map (docs/square_markers.md, "Several squares"). A square's dash
  // pattern is recognised when its dashed sides keep that pattern's phase (mean dash coherence,
  // dash_pattern.hpp, at least min_dash_coherence; about 0.6 for the right pattern, near 0 for
  // another). Squares of one pattern are told apart by the Localizer's last pose, if it is at
  // most max_prior_age seconds old and one of them puts the robot within max_prior_distance
  // metres of it; with several squares a pose must always be that near a recent last pose.
  double min_dash_coherence = 0.3;
  double max_prior_age = 2.0;
  double max_prior_distance = 1.0;
};

}  // namespace irloc::square
