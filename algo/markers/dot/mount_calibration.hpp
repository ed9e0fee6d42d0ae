#pragma once
// The paper's compensation of the camera's offset from the robot's rotation centre, calibrated
// by spinning in place. Poses estimated with the mount's x-y offset set to zero place the base at
// the camera's axis, p_k = c + R(yaw_k) t: while the robot spins about its centre c, they trace a
// circle of radius |t|. A least-squares circle fit gives c; each pose then gives
// t = R(yaw_k)^T (p_k - c), and their mean is the mount's x-y offset t in the base frame.
// Start-up / tool code: no per-frame constraints.

#include <span>

#include <Eigen/Core>

namespace irloc::dot {

struct PlanarPose {
  double x = 0, y = 0, yaw = 0;  // metres, radians
};

struct MountOffsetFit {
  bool ok = false;                                  // false: too few poses, too little turning, or degenerate
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // rotation centre in W, metres
  double radius = 0;                                 // |t|, metres
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  // t: camera axis from the rotation centre, base frame
  double circle_rms = 0;                             // RMS distance of the poses from the circle, metres
  double turned = 0;                                 // yaw range covered, radians (unwrapped)
};

// Kasa's algebraic circle fit refined by Gauss-Newton on the geometric distances. Needs >= 8
// poses covering at least min_turn radians of yaw.
MountOffsetFit fit_mount_offset(std::span<const PlanarPose> poses, double min_turn = 3.14159);

}  // namespace irloc::dot
