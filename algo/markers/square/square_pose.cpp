#include "algo/markers/square/square_pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "algo/geometry/planar_fit.hpp"
#include "algo/geometry/pose_solver.hpp"
#include "algo/markers/square/square_map_checks.hpp"

namespace irloc::square {
namespace {

constexpr std::size_t kMaxCorners = 4 * kMaxSquaresInView;

}  // namespace

SquarePoser::SquarePoser(const CameraModel& camera, const CeilingPlaneMap& plane, const RigidTransform& base_from_camera,
                         Dof dof, std::span<const SquareMarker> markers, const SquareConfig& config)
    : camera_(camera),
      plane_(plane),
      base_from_camera_(base_from_camera),
      dof_(dof),
      markers_(markers),
      config_(config),
      side_(mean_side(markers.front())),
      ceiling_z_(ceiling_z_of(markers.front())) {}

SquareDetection SquarePoser::solve(std::span<const IdentifiedSquare> seen, SquareDetection detection) const {
  // Pose from the corners' rays (plane points at the table's nominal height h0).
  const double h0 = plane_.ceiling_above_camera();
  const Eigen::Matrix3d camera_from_base = base_from_camera_.rotation.transpose();
  std::array<Eigen::Vector3d, kMaxCorners> bearings;
  std::array<Eigen::Vector3d, kMaxCorners> world;
  const std::size_t corners = 4 * seen.size();
  for (std::size_t k = 0; k < corners; ++k) {
    const Eigen::Vector2d& plane = seen[k / 4].corners[k % 4];
    bearings[k] = camera_from_base * Eigen::Vector3d(plane.x(), plane.y(), h0);
    world[k] = markers_[seen[k / 4].square].corners[k % 4];
  }
  if (dof_ == Dof::full6) return solve_tilted(seen, {world.data(), corners}, {bearings.data(), corners}, detection);
  if (!level_pose_from_ceiling({world.data(), corners}, {bearings.data(), corners}, ceiling_z_, base_from_camera_,
                               dof_, detection.world_from_base)) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  // The measured corners, scaled to the found height and carried into W.
  const RigidTransform& pose = detection.world_from_base;
  const double scale = (ceiling_z_ - pose.translation.z() - base_from_camera_.translation.z()) / h0;
  const Eigen::Vector2d camera_xy = base_from_camera_.translation.head<2>();
  std::array<Eigen::Vector2d, kMaxCorners> corners_in_base, on_ceiling, pixels;
  for (std::size_t k = 0; k < corners; ++k) {
    corners_in_base[k] = camera_xy + scale * seen[k / 4].corners[k % 4];
    on_ceiling[k] = (pose * Eigen::Vector3d(corners_in_base[k].x(), corners_in_base[k].y(), 0)).head<2>();
    pixels[k] = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    camera_.project(bearings[k], pixels[k]);
  }
  // The covariance is that of the rigid fit of the corners.
  const Eigen::Matrix<double, 6, 6> unit_covariance = level_fit_covariance(
      {corners_in_base.data(), corners}, camera_xy, scale * h0, rpy_from_rotation(pose.rotation).yaw, 1.0, dof_);
  return finish_pose(seen, {on_ceiling.data(), corners}, {pixels.data(), corners}, unit_covariance, detection);
}

// A tilting robot (dof 6): the square was found on the level table, where a few degrees of tilt
// only skew it a little; the pose is the full 6-dof fit of the corners' pixels (the dot path's
// solver: among the planar target's two poses the nearer to level). The checks are those of the
// level fit, on the corners' rays carried to the ceiling from the fitted pose.
SquareDetection SquarePoser::solve_tilted(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector3d> world,
                                             std::span<const Eigen::Vector3d> bearings, SquareDetection detection) const {
  std::array<Eigen::Vector2d, kMaxCorners> pixels;
  const std::size_t corners = world.size();
  for (std::size_t k = 0; k < corners; ++k) {
    if (!camera_.project(bearings[k], pixels[k])) {
      detection.outcome = SquareOutcome::inconsistent;
      return detection;
    }
  }
  RefinementOptions options;
  options.dof = Dof::full6;
  options.loss = RobustLoss::none;  // four corners: nothing to outvote
  const PoseFit fit = estimate_pose(world, {pixels.data(), corners}, camera_, base_from_camera_, options);
  if (!fit.ok) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  detection.world_from_base = fit.world_from_base;
  const RigidTransform world_from_camera = fit.world_from_base * base_from_camera_;
  std::array<Eigen::Vector2d, kMaxCorners> on_ceiling;
  for (std::size_t k = 0; k < corners; ++k) {
    const Eigen::Vector3d ray = world_from_camera.rotation * bearings[k];
    if (ray.z() <= 0) {
      detection.outcome = SquareOutcome::inconsistent;
      return detection;
    }
    on_ceiling[k] = (world_from_camera.translation + ray * ((ceiling_z_ - world_from_camera.translation.z()) / ray.z())).head<2>();
  }
  // The fit's covariance is for its assumed pixel sigma; per m^2 of corner noise on the ceiling it
  // is scaled by the pixels per metre at the ceiling's distance on the axis.
  const double pixels_per_metre = camera_.intrinsics().fx / plane_.ceiling_above_camera();
  const Eigen::Matrix<double, 6, 6> unit_covariance =
      fit.covariance * (pixels_per_metre * pixels_per_metre / (options.pixel_sigma * options.pixel_sigma));
  return finish_pose(seen, {on_ceiling.data(), corners}, {pixels.data(), corners}, unit_covariance, detection);
}

SquareDetection SquarePoser::finish_pose(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector2d> on_ceiling,
                                            std::span<const Eigen::Vector2d> pixels,
                                            const Eigen::Matrix<double, 6, 6>& unit_covariance, SquareDetection detection) const {
  // Consistency: the measured corners against the map's, each side against d.
  const std::size_t corners = on_ceiling.size();
  double squared = 0;
  double worst_side_error = 0;
  for (std::size_t k = 0; k < corners; ++k) {
    const std::size_t next = 4 * (k / 4) + (k + 1) % 4;
    squared += (on_ceiling[k] - markers_[seen[k / 4].square].corners[k % 4].head<2>()).squaredNorm();
    worst_side_error = std::max(worst_side_error, std::abs((on_ceiling[next] - on_ceiling[k]).norm() - side_) / side_);
  }
  detection.corner_rms = std::sqrt(squared / static_cast<double>(corners));
  if (detection.corner_rms > config_.max_corner_residual || worst_side_error > config_.max_side_error) {
    detection.outcome = SquareOutcome::inconsistent;
    return detection;
  }
  // Confidence: how much of the square was seen (the detection's as given), times how well it matches
  // the map.
  const double fit_quality = 1 - detection.corner_rms / config_.max_corner_residual;
  detection.confidence = std::clamp(detection.confidence * fit_quality, 0.0, 1.0);
  // Corner noise sigma ~ corner_rms * sqrt(4 / (4 - 3)) (three pose parameters from eight
  // numbers), at least 2 mm.
  const double corner_sigma = std::max(detection.corner_rms * 2.0, 0.002);
  detection.covariance = unit_covariance * (corner_sigma * corner_sigma);
  detection.square_count = seen.size();
  for (std::size_t k = 0; k < corners; ++k) {
    detection.squares[k / 4] = static_cast<int>(seen[k / 4].square);
    detection.corner_pixels[k / 4][k % 4] = pixels[k];
  }
  detection.outcome = SquareOutcome::found;
  return detection;
}

}  // namespace irloc::square
