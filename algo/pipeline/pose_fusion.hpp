#pragma once
// One pose from two landmark paths that both saw something (the paper's proposal: square and dot
// markers together): an inverse-variance weighted mean of two level poses, gated so that two
// poses that disagree (one of them is wrong, and nothing says which) give no pose at all.

#include <span>

#include <Eigen/Core>

namespace irloc {

// A level pose (roll = pitch = 0) with rough 1-sigma uncertainties: position per axis (x, y and
// z), metres; yaw, radians.
struct LevelPose {
  double x = 0, y = 0, z = 0, yaw = 0;
  double position_sigma = 0;
  double yaw_sigma = 0;
};

struct FusionGate {
  double position = 0.10;  // metres between the two positions
  double yaw = 0.05;       // radians between the two headings (about 3 degrees)
};

// Weighted mean of a and b (weights 1 / sigma^2, yaw averaged on the circle), with the combined
// sigmas. false when they disagree beyond the gate or a sigma is not positive.
bool fuse_level_poses(const LevelPose& a, const LevelPose& b, const FusionGate& gate, LevelPose& fused);

// Uncertainty of a pose fitted to n ceiling points seen with pixel noise sigma_px: each point
// has footprint metres per pixel on the ceiling; translation averages the points, yaw uses
// their spread about the centroid (lever arm). footprints and world_points: one per point.
void point_fit_uncertainty(std::span<const double> footprints, std::span<const Eigen::Vector2d> world_points,
                           double sigma_px, LevelPose& pose);

}  // namespace irloc
