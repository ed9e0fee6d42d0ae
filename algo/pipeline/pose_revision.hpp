#pragma once
// Whether a revision of a pose (the same frame's pose found again from a later attempt:
// Localizer::revised_previous) agrees with what the pose claimed.

#include "algo/geometry/pose.hpp"
#include "algo/pipeline/pose_estimate.hpp"

namespace irloc {

// The revision is refused beyond the chi-square value of 3 degrees of freedom (x, y, yaw) that
// this normal quantile's tail gives (3: as rare as a deviation of 3 sigma one way, 0.13 %).
inline constexpr double kRevisionGateNormalQuantile = 3.0;

// Whether `revised` lies within the gate of `first` over x, y and yaw (Mahalanobis distance,
// under the sum of first's covariance and `revised_from`, the covariance of the pose the revision
// was taken from; the yaw difference wrapped). Beyond it the revision contradicts the first pose
// and nothing says which one is wrong. False also where that sum is not positive definite on x, y
// and yaw. Allocation-free.
bool revision_agrees(const PoseEstimate& first, const PoseEstimate& revised, const PoseCovariance& revised_from);

}  // namespace irloc
