#pragma once
// The rules a map's square markers must keep for the square path (SquareDetector): each a level
// square above the camera, all of one side, tape width and ceiling height (one ceiling table and
// one Hough search serve them all), their dash patterns equal or told apart by their periods.

#include <span>
#include <vector>

#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"

namespace irloc::square {

// Two dash patterns are told apart by their periods (dash + gap); closer than this they are refused.
inline constexpr double kMinDashPeriodRatio = 1.5;

// The mean of the marker's four sides, metres.
double mean_side(const SquareMarker& marker);
// The mean height of its corners in W, metres.
double ceiling_z_of(const SquareMarker& marker);
// The markers, when they keep the rules; else std::invalid_argument naming the marker(s).
std::vector<SquareMarker> checked_square_markers(std::span<const SquareMarker> markers);
// Its height above the camera (base_from_camera: the camera in B, the robot level at z = 0);
// std::invalid_argument naming it when it is not more than 0.1 m above.
double ceiling_above_camera(const SquareMarker& marker, const RigidTransform& base_from_camera);

}  // namespace irloc::square
