#pragma once
// Solid or dashed: how much of a side's visible length is covered by tape. Tape points are
// binned along the side; a long empty stretch (longer than a gap) is taken as hidden (a person,
// the edge of the view), not as evidence, so a half-hidden solid side still reads as solid:
// fill ~ 1 for the solid side, ~ dash / (dash + gap) for a dashed one.

#include <span>

#include <Eigen/Core>

#include "algo/kernels/hough_lines.hpp"

namespace irloc {

struct DashPattern {
  double visible_fraction = 0;  // of the side between the corner patches
  double fill = 0;              // of the visible length
};

struct DashGeometry {
  double tape_width = 0.05;
  double dash = 0.10;
  double gap = 0.10;
};

// The side from start to end (metres on the ceiling plane); points within tape_width of it count.
DashPattern measure_dash_pattern(std::span<const PlanePoint> points, const Eigen::Vector2d& start,
                                 const Eigen::Vector2d& end, const DashGeometry& geometry);

}  // namespace irloc
