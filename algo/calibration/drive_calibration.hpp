#pragma once
// Self-calibration from the ceiling: a bundle adjustment over a drive under mapped dot markers
// that refines the camera's intrinsics (its own lens model) and the mount T_B_C, together with
// every robot pose of the drive (in the robot's dof), from every dot of every decoded marker.
//
// Unknowns: the lens parameters (lens_parameters.hpp), the mount (rotation about the base's
// x, y, z axes and its x, y, z offset), and per pose x, y, yaw (dof 3), + z (dof 4), + roll,
// pitch (dof 6). Residuals: the dots' reprojection errors in pixels (Huber loss), the robot's
// non-holonomic motion (its base does not slide sideways: between consecutive poses the
// displacement across the mean heading is ~0), and the priors below. Levenberg-Marquardt on the
// normal equations, solved by Eigen's sparse Cholesky (SimplicialLDLT); each parameter's sigma
// from the inverse normal matrix, scaled by the pixel noise the residuals show.
//
// Observability, handled explicitly (docs/calibration.md):
// - Principal point vs a shift of every pose (and nearly the mount tilt): to a camera looking up
//   at a plane each shifts the whole image. The principal point has a prior (input +-
//   principal_point_sigma_px), but it is judged without it: unless the drive alone observes it
//   (max_lens_effect_px), it is kept at its input value. A prior is no evidence, and its pull
//   moved a correct principal point on drives that cannot show it.
// - Camera height vs focal length: a ceiling seen face-on fixes only focal / height (with the
//   distortion scaled alongside). dof 3: the mount's z has a prior (input +- mount_sigma_m);
//   dof 4 and 6: the mount's z is fixed (every pose's z is an unknown of its own) and fx has a
//   prior (input +- focal_length_sigma).
// - Mount x, y: the non-holonomic prior ties the camera to the base's axle line when the robot
//   turns, which gives the mount's x (distance from the axle) and yaw (the direction of travel);
//   the offset along the axle (y) has a prior only (input +- mount_sigma_m): no motion of a
//   wheeled base shows where on its axle its origin lies.
// - dof 6: the mount's roll and pitch are fixed (every pose has its own roll and pitch).
// - Any other parameter whose sigma stays too large on this drive (k3 without dots far out,
//   mount x without turning, ...) is kept at its input value with the reason, and the rest is
//   solved again.
// - What the drive's motion cannot show is decided from the motion itself, before any solve
//   (repeated frames of one view make the sigmas look small): fewer than min_views distinct
//   views refuse the calibration; the mount's x needs min_turn_rad of turning, its yaw
//   min_drive_m of driving.
// - Evidence: the refined parameters are returned only when their change from the input is
//   significant in their own covariance (a chi-square test at evidence_probability, the
//   covariance widened by frames / views, since frames of nearly one view are not independent).
//   A change the drive's noise explains is no evidence against the input, and writing it could
//   only make the calibration worse.
//
// Offline: runs once at the end of a drive and allocates (bounded by the drive's size).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "algo/calibration/drive_observations.hpp"
#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::calibration {

struct CalibrationOptions {
  Dof dof = Dof::planar3;
  double loss_scale_px = 1.5;             // Huber scale of the dots' reprojection errors
  double principal_point_sigma_px = 5.0;  // prior on cx, cy around their input values
  double mount_sigma_m = 0.005;           // prior on the mount's y (and z under dof 3), tape-measure accuracy
  double focal_length_sigma = 0.01;       // dof 4 and 6: prior on fx, relative to its input value
  double lateral_slip_sigma_m = 0.0005;   // sideways slip per step between consecutive poses
  double max_step_seconds = 0.5;          // consecutive poses further apart in time are not linked
  int max_iterations = 60;                // Levenberg-Marquardt, per solve
  // Observability: a parameter is kept at its input value when, on this drive, its sigma would
  // move the dots by more than max_lens_effect_px (lens parameters, at the most sensitive dot),
  // or exceed these (mount).
  double max_lens_effect_px = 0.5;
  double max_mount_rotation_sigma_rad = 0.0087;  // 0.5 degree
  double max_mount_offset_sigma_m = 0.02;
  // Motion: a view is a pose at least view_spacing_m or view_spacing_rad from the last view.
  int min_views = 10;
  double view_spacing_m = 0.1;
  double view_spacing_rad = 0.17;  // 10 degrees
  double min_turn_rad = 0.79;      // 45 degrees of turning show the mount's x
  double min_drive_m = 0.5;        // driving shows the mount's yaw
  double evidence_probability = 0.999;  // chance a correct input passes the evidence test
  // Practical evidence: the refined calibration must explain the dots this fraction better (RMS)
  // than the input does with every pose refined to it. The statistical test alone trusts sigmas
  // from the dots' scatter, which leave out the detector's own systematic errors.
  double min_residual_gain = 0.1;
};

enum class ParameterState {
  estimated,    // from the drive
  prior_bound,  // estimated, but its sigma is mostly the prior's (the drive adds little)
  fixed,        // kept at its input value; `reason` says why
};

struct ParameterEstimate {
  std::string name;  // "fx", ..., "mount roll" (rotation about base x), "mount x", ...
  std::string unit;  // "px", "", "rad", "m"
  double input = 0;  // mount rotations: 0 (they are changes from the input rotation)
  double value = 0;
  double sigma = 0;  // 1-sigma; 0 when fixed
  ParameterState state = ParameterState::estimated;
  std::string reason;  // for prior_bound and fixed
};

struct ResidualStats {
  std::size_t count = 0;  // dots in the valid region of the lens
  double rms_px = 0;      // of the 2-D reprojection error
  double median_px = 0;
  double max_px = 0;
};

struct DotResidual {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();   // measured
  Eigen::Vector2d before = Eigen::Vector2d::Zero();  // projected - measured, input calibration
  Eigen::Vector2d after = Eigen::Vector2d::Zero();   // the same, refined calibration
};

struct CalibrationResult {
  bool ok = false;
  std::string message;  // why not ok
  CameraIntrinsics camera;
  RigidTransform mount;  // T_B_C
  std::vector<ParameterEstimate> parameters;  // lens parameters, then the mount's six
  ResidualStats before, after;
  double pixel_sigma = 0;  // the dots' noise the final residuals show, px (scales every sigma)
  std::vector<RigidTransform> poses;  // refined T_W_B, one per drive frame
  std::vector<DotResidual> residuals;  // one per observation
  double turned_rad = 0;    // total |yaw change| over the drive
  double driven_m = 0;      // path length
  double duration_s = 0;
  int views = 0;            // distinct views (CalibrationOptions::view_spacing_*)
  double change_chi2 = 0;   // the change from the input in its covariance (widened by frames / views)
  double chance_chi2 = 0;   // what noise reaches with probability 1 - evidence_probability
  double input_refit_rms_px = 0;  // the dots' RMS with the input calibration and every pose refined to it
  double rms_limit_px = 0;        // what the refined calibration's RMS must be below (min_residual_gain)
  int iterations = 0;
};

// The drive needs at least 10 frames and min_views views; ok only when it shows evidence against
// the input (message says why not). camera and mount are the input calibration (the one the
// drive's poses were computed with).
CalibrationResult calibrate_from_drive(const DriveObservations& drive, const CameraIntrinsics& camera,
                                       const RigidTransform& mount, const CalibrationOptions& options);

}  // namespace irloc::calibration
