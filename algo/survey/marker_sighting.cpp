#include "algo/survey/marker_sighting.hpp"

#include <algorithm>
#include <array>

#include <Eigen/LU>

#include "algo/geometry/pose_solver.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::survey {

namespace {

// The fit's linear answer to the dots' pixel errors: with J the Jacobian of the dots' pixels by
// the pose (x, y, z, yaw) and C = (J^T J)^-1, the error C J^T e has the covariance
// C J^T (I x F) J C, which splits by the entries of F into the rows of J along u and along v.
// J by central differences (the pose solver keeps its own): 8 poses, each dot projected from
// each; no heap.
PixelErrorResponse pixel_error_response(const CeilingPose& base_in_level, std::span<const Eigen::Vector3d> points,
                                        const CameraModel& camera, const RigidTransform& base_from_camera) {
  constexpr double kStep = 1e-6;  // m or rad
  std::array<Eigen::Matrix<double, 2, 4>, dot::kCellCount> jacobians;
  for (int k = 0; k < 4; ++k) {
    for (const double side : {1.0, -1.0}) {
      CeilingPose pose = base_in_level;
      pose[k] += side * kStep;
      const RigidTransform camera_from_level = (to_transform(pose) * base_from_camera).inverse();
      for (std::size_t i = 0; i < points.size(); ++i) {
        Eigen::Vector2d projected;
        if (!camera.project(camera_from_level * points[i], projected)) return {};
        if (side > 0) jacobians[i].col(k) = projected;
        else jacobians[i].col(k) = (jacobians[i].col(k) - projected) / (2 * kStep);
      }
    }
  }
  CeilingCovariance information = CeilingCovariance::Zero(), along_u = information, coupling = information;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector4d u = jacobians[i].row(0).transpose(), v = jacobians[i].row(1).transpose();
    information += u * u.transpose() + v * v.transpose();
    along_u += u * u.transpose();
    coupling += u * v.transpose() + v * u.transpose();
  }
  const CeilingCovariance inverse = information.inverse();
  PixelErrorResponse response;
  response.along_u = inverse * along_u * inverse;
  response.along_v = inverse - response.along_u;
  response.coupling = inverse * coupling * inverse;
  return response;
}

}  // namespace

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
  sighting.pixel_error_response = pixel_error_response(sighting.base_in_marker, point_span, camera, base_from_camera);
  return true;
}

}  // namespace irloc::survey
