#pragma once
// Closed-form fits for markers on a flat, horizontal ceiling seen by a level robot.
//
// A level robot (roll = pitch = 0: robot.dof 3 or 4) knows its camera's rays in a frame that
// differs from W only by yaw and a translation. Cut by the ceiling plane, the rays give the
// markers' points in that frame, and the pose is a 2-D rigid fit (dof 3: the ceiling height above
// the camera is known) or a 2-D similarity fit (dof 4: the scale is that height). A mirrored pose
// cannot arise: it would need roll or pitch. No heap.

#include <span>

#include <Eigen/Core>

#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

// to ~ scale * R(yaw) * from + translation.
struct PlanarTransform {
  double yaw = 0;
  double scale = 1;
  Eigen::Vector2d translation = Eigen::Vector2d::Zero();
};

// Least-squares rigid (scale 1) and similarity fits of to[i] ~ T(from[i]). Spans of equal size,
// at least 2 points, not all coincident; false otherwise.
bool fit_rigid_2d(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to,
                  PlanarTransform& fit);
bool fit_similarity_2d(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to,
                       PlanarTransform& fit);

// T_W_B of a level robot (dof 3 or 4) from points on the horizontal plane z = ceiling_z of W and
// their bearings in the camera frame (unit or not). dof 3 puts the base on z = 0; dof 4 finds z.
// false for dof 6, fewer than 2 points, a bearing not pointing up, or a degenerate fit.
// Uses at most kMaxCeilingPoints points (the first ones).
inline constexpr std::size_t kMaxCeilingPoints = 64;
bool level_pose_from_ceiling(std::span<const Eigen::Vector3d> world_points,
                             std::span<const Eigen::Vector3d> bearings_c, double ceiling_z,
                             const RigidTransform& base_from_camera, Dof dof, RigidTransform& world_from_base);

// Covariance of (x, y, z, roll, pitch, yaw) of a level pose T_W_B fitted to points seen in the
// ceiling plane, each with isotropic noise sigma (metres): sigma^2 (J^T J)^-1 of the fit
// world_i = R(yaw) (c + (p_i - c) h(z) / h) + (x, y), p_i the points in base coordinates, c
// the camera's x-y in the base, h the ceiling's height above the camera. dof 3 estimates x, y,
// yaw; dof 4 also z (the points' scale). The rows of the other parameters are zero; dof 6 is
// not a level fit and gives zero.
Eigen::Matrix<double, 6, 6> level_fit_covariance(std::span<const Eigen::Vector2d> points_in_base,
                                                  const Eigen::Vector2d& camera_xy, double height_above_camera,
                                                  double yaw, double sigma, Dof dof);

}  // namespace irloc
