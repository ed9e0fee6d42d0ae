#include "algo/survey/marker_sighting.hpp"

#include <algorithm>
#include <array>

#include "algo/geometry/pose_solver.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::survey {

bool fit_sighting(std::span<const PointObservation> dots, double pitch, const CameraModel& camera,
                  const RigidTransform& base_from_camera, const SurveyConfig& config, MarkerSighting& sighting) {
  if (dots.size() < std::max<std::size_t>(config.min_dots, 3) || dots.size() > dot::kCellCount) return false;
  std::array<Eigen::Vector3d, dot::kCellCount> points;
  std::array<Eigen::Vector2d, dot::kCellCount> pixels;
  for (std::size_t i = 0; i < dots.size(); ++i) {
    // M -> L flips y and z: a cell at (j p, i p, 0) in M is at (j p, -i p, 0) in L.
    const Eigen::Vector3d in_marker = dot::cell_in_marker(dots[i].point, pitch);
    points[i] = {in_marker.x(), -in_marker.y(), 0.0};
    pixels[i] = dots[i].pixel;
  }
  RefinementOptions options;
  options.dof = Dof::height4;
  options.loss_scale_px = config.refine_loss_scale_px;
  const std::span<const Eigen::Vector3d> point_span(points.data(), dots.size());
  const std::span<const Eigen::Vector2d> pixel_span(pixels.data(), dots.size());
  const PoseFit fit = estimate_pose(point_span, pixel_span, camera, base_from_camera, options);
  if (!fit.ok) return false;

  constexpr std::array<int, 4> kIndex = {0, 1, 2, 5};  // x, y, z, yaw of the 6-vector
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) sighting.covariance(r, c) = fit.covariance(kIndex[r], kIndex[c]);
  }
  sighting.covariance /= options.pixel_sigma * options.pixel_sigma;
  sighting.squared_residuals = fit.cost;
  sighting.redundancy = 2.0 * static_cast<double>(dots.size()) - 4.0;
  sighting.base_in_marker = ceiling_pose_from(fit.world_from_base);
  sighting.id = dots[0].landmark;
  const RigidTransform camera_from_level = (fit.world_from_base * base_from_camera).inverse();
  sighting.cells = 0;
  for (std::size_t i = 0; i < dots.size(); ++i) {
    Eigen::Vector2d projected;
    if (!camera.project(camera_from_level * points[i], projected)) continue;
    if (dots[i].point < 0 || dots[i].point >= dot::kCellCount) continue;
    sighting.residuals.col(dots[i].point) = pixels[i] - projected;
    sighting.cells = static_cast<dot::CellMask>(sighting.cells | (1u << dots[i].point));
  }
  return true;
}

}  // namespace irloc::survey
