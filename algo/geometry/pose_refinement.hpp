#pragma once
// Nonlinear least-squares refinement of a robot pose T_W_B from known world points and their
// pixels, seen by a calibrated camera on a known mount T_B_C.
//
// Parameters: x, y, z, roll, pitch, yaw of T_W_B (R_W_B = Rz(yaw) Ry(pitch) Rx(roll), as in
// docs/conventions.md). robot.dof chooses which are estimated; the others are constraints:
//   dof 3: x, y, yaw   (z = roll = pitch = 0)
//   dof 4: x, y, z, yaw (roll = pitch = 0)
//   dof 6: all six (Euler angles: singular only at pitch = +-pi/2, never met by a ground robot)
// Levenberg-Marquardt on the reprojection error in pixels with a robust loss (iteratively
// reweighted). No heap.

#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

enum class RobustLoss {
  none,    // plain least squares
  huber,   // quadratic up to loss_scale_px, linear beyond
  cauchy,  // log(1 + (e / loss_scale_px)^2): distant outliers lose all influence
};

// Robust weight (iteratively reweighted least squares) of a reprojection error e >= 0 (pixels),
// and its cost (e^2 where the loss is quadratic).
double robust_weight(RobustLoss loss, double scale, double error);
double robust_cost(RobustLoss loss, double scale, double error);

struct RefinementOptions {
  Dof dof = Dof::planar3;
  RobustLoss loss = RobustLoss::huber;
  double loss_scale_px = 2.0;    // pixels: where the robust loss departs from quadratic
  double pixel_sigma = 0.5;      // pixels: the assumed standard deviation of one pixel coordinate
  int max_iterations = 30;
  // > 0: converged once an accepted step moved the pose by less than this many of its standard
  // deviations (at pixel_sigma: step^T N step <= (stop_step_sigmas pixel_sigma)^2, N the step's
  // damped J^T W J), the pose then closer than that to the minimum. 0: only where the cost stops decreasing (1e-12
  // relative), which at residuals of the pixel noise is the cost's rounding floor, met after
  // rejected steps.
  double stop_step_sigmas = 0;
  // The pose sources' choice: within a thousandth of the pose's standard deviation of the minimum,
  // far below its noise.
  static constexpr double kSourceStopStepSigmas = 1e-3;
  // radians: how far from level a ground robot's base plausibly tilts. Only estimate_pose under
  // dof 6 uses it, to choose between candidates the pixels cannot tell apart (a Gaussian prior).
  double level_prior_sigma = 0.17;
};

// A fitted pose with its uncertainty.
struct PoseFit {
  bool ok = false;                 // false: too few points, or a point left the camera's valid region
  RigidTransform world_from_base;  // T_W_B
  // Covariance of (x, y, z, roll, pitch, yaw), m^2 / rad^2: pixel_sigma^2 (J^T W J)^-1 at the
  // solution (W: the robust weights). Rows and columns of constrained parameters are zero.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  double rms_px = 0;               // root mean square reprojection error (per point, 2-D norm)
  double cost = 0;                 // the robust cost that was minimized, pixels^2
  int iterations = 0;
};

// The pose parameters (x, y, z, roll, pitch, yaw) of T_W_B, and back.
using PoseParameters = Eigen::Matrix<double, 6, 1>;
PoseParameters parameters_from_pose(const RigidTransform& world_from_base);
RigidTransform pose_from_parameters(const PoseParameters& parameters);

// Projects a constrained pose onto the dof: dof 3 zeroes z, roll and pitch; dof 4 roll and
// pitch; dof 6 leaves it.
RigidTransform constrain_pose(const RigidTransform& world_from_base, Dof dof);

// world_points[i] (W, metres) is seen at pixels[i]; the spans have the same size. The initial
// pose is first constrained to the dof. At least ceil(dof / 2) points are needed.
PoseFit refine_pose(std::span<const Eigen::Vector3d> world_points, std::span<const Eigen::Vector2d> pixels,
                    const CameraModel& camera, const RigidTransform& base_from_camera,
                    const RigidTransform& initial_world_from_base, const RefinementOptions& options);

}  // namespace irloc
