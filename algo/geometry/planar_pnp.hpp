#pragma once
// The pose of a calibrated camera from points of a plane (z = 0 in the plane's frame P) and their
// pixels: IPPE (Collins & Bartoli, "Infinitesimal Plane-Based Pose Estimation", IJCV 2014) gives
// the two poses that the local affine view of the plane allows, each is refined by
// Gauss-Newton / Levenberg-Marquardt on the reprojection error in pixels through the lens model,
// and the one of lower error wins. Four or more points, no three of them need be a rectangle.
// No heap.
#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

struct PlanarPose {
  bool ok = false;                  // false: fewer than 4 points, degenerate points, or a point behind the camera
  RigidTransform camera_from_plane; // T_C_P
  // Information of the pose, px^-2: J^T J of the pixel residuals over the perturbation
  // T_C_P' = (exp([w]x) R, t + dt), parameters (w, dt) in C (rad, m). Times the pixel variance's
  // inverse it is the inverse covariance.
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  double sum_squares_px2 = 0;       // of the pixel residuals at the solution
  double other_sum_squares_px2 = 0; // of IPPE's other candidate after refinement (infinity if none)
};

// plane_points[i] (P, metres, z = 0) is seen at pixels[i]; spans of equal size, at least 4.
PlanarPose solve_planar_pnp(std::span<const Eigen::Vector2d> plane_points, std::span<const Eigen::Vector2d> pixels,
                            const CameraModel& camera);

}  // namespace irloc
