#pragma once
// Stage 5: the robot pose from the decoded, mapped markers in view. As in the paper, P3P on the
// direction dots O, X, Y of the marker closest to the image centre gives the starting poses; then
// every dot of every marker refines the pose under robot.dof (Levenberg-Marquardt, Huber loss:
// algo/geometry/pose_refinement.hpp). A marker whose dots do not fit the common pose (RMS above
// the gate: a mis-decoded or moved marker) is dropped and the rest refit.

#include <cstddef>
#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/markers/dot/dot_confidence.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::dot {

// One decoded marker whose ID is in the map.
struct MarkerObservation {
  int id = -1;
  std::uint8_t dot_count = 0;
  std::array<std::uint8_t, kCellCount> cells{};          // cell of each dot
  std::array<Eigen::Vector3d, kCellCount> world{};       // W, metres
  std::array<Eigen::Vector2d, kCellCount> pixels{};      // px
  Eigen::Vector2d centre_pixel = Eigen::Vector2d::Zero();  // mean of the dots' pixels
  MarkerEvidence evidence;
  bool used = false;  // set by solve_dot_pose: kept in the final fit
  bool identified_by_track = false;  // named by the track, not decoded (track_identification.hpp)
};

inline constexpr std::size_t kMaxMarkersInView = 8;
using MarkerObservationList = StaticVector<MarkerObservation, kMaxMarkersInView>;

struct DotPoseOptions {
  RefinementOptions refinement;
  double marker_gate_px = 3.0;
};

struct DotPoseResult {
  PoseFit fit;               // fit.ok false: no pose
  int reference_marker = -1; // index of the marker the P3P start came from
  int markers_used = 0;
};

// markers: their `used` flags are set (false for markers left out of the final fit). A reference
// marker without all of O, X, Y (one identified by the track) starts from a well-spread triple of
// the dots and the level ceiling fit (estimate_pose) instead.
DotPoseResult solve_dot_pose(std::span<MarkerObservation> markers, const CameraModel& camera,
                             const RigidTransform& base_from_camera, const DotPoseOptions& options);

// The same markers' pose again after their world points moved a little (a rolling shutter's points
// moved to t_ns for a better motion, rolling_shutter.hpp): when last used every marker, their dots
// refined from start (one refinement, where solve_dot_pose refines every P3P start), with last's
// reference. Else (last left a marker out: whether the gate keeps it out is the full solve's
// question; or last has no pose), or when the refinement fails or a marker fails the gate,
// solve_dot_pose.
DotPoseResult refit_dot_pose(std::span<MarkerObservation> markers, const CameraModel& camera,
                             const RigidTransform& base_from_camera, const DotPoseOptions& options,
                             const DotPoseResult& last, const RigidTransform& start);

}  // namespace irloc::dot
