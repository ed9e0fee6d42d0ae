#pragma once
// The square path's pose stage: the robot's pose from the corners of the map squares seen (one,
// or several at one pose: fused), with the consistency checks against the map, the confidence
// and the covariance. Level (dof 3, 4): the rigid fit of the corners on the ceiling plane; dof 6:
// the 6-dof fit of their pixels. Allocates nothing.

#include <array>
#include <cstddef>
#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/square_config.hpp"
#include "algo/markers/square/square_detection.hpp"

namespace irloc::square {

// A hypothesis identified: the map square (an index into the markers) and its corners c0..c3 on
// the ceiling plane, metres.
struct IdentifiedSquare {
  std::size_t square = 0;
  std::array<Eigen::Vector2d, 4> corners;
};

class SquarePoser {
 public:
  // Keeps references to camera, plane, markers and config: they outlive it. markers: checked
  // (square_map_checks.hpp).
  SquarePoser(const CameraModel& camera, const CeilingPlaneMap& plane, const RigidTransform& base_from_camera, Dof dof,
              std::span<const SquareMarker> markers, const SquareConfig& config);

  // seen: at most kMaxSquaresInView. detection.confidence in: how much of the square was seen;
  // out: that times the fit's quality. Sets the pose, corner RMS, covariance, squares and corner
  // pixels and outcome found, or outcome inconsistent; the rest of detection is kept.
  SquareDetection solve(std::span<const IdentifiedSquare> seen, SquareDetection detection) const;

 private:
  SquareDetection solve_tilted(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector3d> world,
                               std::span<const Eigen::Vector3d> bearings, SquareDetection detection) const;
  // The tail of both: on_ceiling (x-y in W of the corners, from the fitted pose) checked against
  // the map, the confidence, the covariance (unit_covariance times the corners' noise variance in
  // m^2), the squares and their corners' pixels.
  SquareDetection finish_pose(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector2d> on_ceiling,
                              std::span<const Eigen::Vector2d> pixels, const Eigen::Matrix<double, 6, 6>& unit_covariance,
                              SquareDetection detection) const;

  const CameraModel& camera_;
  const CeilingPlaneMap& plane_;
  RigidTransform base_from_camera_;
  Dof dof_;
  std::span<const SquareMarker> markers_;
  const SquareConfig& config_;
  double side_ = 0;       // d from the map, metres
  double ceiling_z_ = 0;  // of the markers in W
};

}  // namespace irloc::square
