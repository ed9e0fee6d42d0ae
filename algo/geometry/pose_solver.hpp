#pragma once
// The pose of the robot from known world points and their pixels: the one pose-solving call of
// the pose sources (the dot marker source solves with it).
//
//   PoseFit fit = estimate_pose(world_points, pixels, camera, base_from_camera, options);
//
// Candidates: the level-robot ceiling fit (when every point lies on one horizontal plane; under
// dof 6 it is a level starting point) and the P3P solutions of a triple (the caller's, such as a
// marker's direction dots, or else a well-spread one). Each is refined under the dof constraints
// (pose_refinement.hpp) and the lowest robust cost wins. Planar targets seen head-on have a
// mirrored pose of nearly equal cost: under dof 3 and 4 the constraints exclude it; under dof 6
// the candidate with the highest posterior wins, cost / pixel_sigma^2 + (tilt / level_prior_sigma)^2
// smallest (tilt: angle of the base z axis from W's z), because a ground robot is far closer to
// level than the mirror image of its pose. No heap.

#include <array>
#include <cstddef>
#include <optional>
#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

// world_points[i] (W, metres) seen at pixels[i]; spans of equal size. Needs 2 points for dof 3 and
// 4 on a horizontal plane, else 3 (3 points under dof 6 are ambiguous: 4 or more are better).
// p3p_triple: indices of the three points the P3P starts come from; by default a well-spread
// triple. fit.ok is false when no candidate could be refined.
using PointTriple = std::array<std::size_t, 3>;
PoseFit estimate_pose(std::span<const Eigen::Vector3d> world_points, std::span<const Eigen::Vector2d> pixels,
                      const CameraModel& camera, const RigidTransform& base_from_camera,
                      const RefinementOptions& options, std::optional<PointTriple> p3p_triple = std::nullopt);

}  // namespace irloc
