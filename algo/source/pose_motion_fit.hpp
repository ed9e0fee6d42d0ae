#pragma once
// The pose at a frame's t_ns and the robot's motion within the frame, fitted together to points
// seen at their rows' times (a rolling shutter: rolling_shutter.hpp). Where the points span many
// rows (several markers at different rows, a marker spanning many), the frame alone tells how the
// robot moved while its rows were read; where they do not, the motion's standard deviations say
// so. Gauss-Newton on the reprojection error over the dof's free pose parameters and the motion
// (the velocity's x and y in the heading frame, the yaw rate; no climb), from a pose and no
// motion (or the prior's mean). With a prior on the motion (the fastest robot's, zero mean; or
// the motion before a gap) the fit is the MAP estimate: it takes from the frame what the points
// show of the motion (one marker's shear and stretch over its rows), keeps the rest near the
// prior's mean, and its covariance says how much that was. Allocation-free.

#include <optional>
#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/source_input.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

struct PoseMotionFit {
  bool ok = false;                 // false: too few points, a point left the camera model, singular
  RigidTransform world_from_base;  // T_W_B at t_ns
  FrameMotion motion;
  // Standard deviations, for the pixel noise the fit's residuals show (at least min_pixel_sigma):
  // the velocity's along its worse axis (m/s), the yaw rate's (rad/s).
  double velocity_sigma = 0;
  double yaw_rate_sigma = 0;
  // What the motion's uncertainty adds to the pose's covariance: the pose block of the joint
  // covariance less the pose's covariance given the motion (a fit to the points moved by it).
  // (x, y, z, roll, pitch, yaw); rows and columns of parameters the dof fixes are zero.
  PoseCovariance motion_pose_covariance = PoseCovariance::Zero();
};

// world[k] (W, metres) was seen at pixels[k], row_times[k] seconds after t_ns (the spans have the
// same size); initial: a pose near the one at t_ns (a plain fit). motion_prior: a prior on the
// motion (source_input.hpp); nullopt: none (the points alone must decide the motion).
PoseMotionFit fit_pose_and_motion(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector2d> pixels,
                                  std::span<const double> row_times, const CameraModel& camera,
                                  const RigidTransform& base_from_camera, const RigidTransform& initial, Dof dof,
                                  double min_pixel_sigma, const std::optional<MotionPrior>& motion_prior);

}  // namespace irloc
