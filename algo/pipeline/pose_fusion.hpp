#pragma once
// One pose from several sources that each found one (the square-marker paper's proposal, square
// and dot markers together, generalised): the inverse-covariance weighted mean over the
// parameters the robot's dof estimates, gated so that poses that disagree (one of them is wrong,
// and nothing says which) give no pose at all.

#include <span>

#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

struct FusionGate {
  double position = 0.10;  // metres between two sources' positions
  double yaw = 0.05;       // radians between two sources' headings (about 3 degrees)
};

struct FusedPose {
  RigidTransform world_from_base;
  PoseCovariance covariance = PoseCovariance::Zero();
};

// results: poses with their covariances (every one ok). The mean is taken in (x, y, z, roll,
// pitch, yaw), angles relative to the first pose so that it is taken on the circle; the fused
// covariance is the inverse of the summed information. false when two poses are further apart
// than the gate, or a covariance is not positive definite on the estimated parameters.
bool fuse_poses(std::span<const SourceResult* const> results, Dof dof, const FusionGate& gate, FusedPose& fused);

}  // namespace irloc
