#include "algo/survey/marker_sighting.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/LU>

#include "algo/geometry/pose_solver.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::survey {

namespace {

// How alike two dots' fixed errors along one image axis are, by how far apart they lie on that
// axis (px): the error is a function of where a dot falls on the pixel grid, so two dots at the
// same place across it (one image column, for the u error) repeat it, and dots a fraction of a
// pixel apart do not. A triangle (positive semi-definite: the self-correlation of a box) of half
// width correlation_px.
double grid_error_correlation(double apart_px, double correlation_px) {
  return std::max(0.0, 1.0 - std::abs(apart_px) / correlation_px);
}

// The fit's linear answer to the dots' pixel errors: with J the Jacobian of the dots' pixels by
// the pose (x, y, z, yaw) and C = (J^T J)^-1, the error C J^T e has the covariance C J^T S J C,
// S the dots' errors' covariance: per axis the pixel error's variance times the dots' correlation
// on that axis (grid_error_correlation()), so that dots in one image column share their u error.
// J by central differences (the pose solver keeps its own): 8 poses, each dot projected from
// each; no heap.
PixelErrorResponse pixel_error_response(const CeilingPose& base_in_level, std::span<const Eigen::Vector3d> points,
                                        const CameraModel& camera, const RigidTransform& base_from_camera,
                                        double correlation_px) {
  constexpr double kStep = 1e-6;  // m or rad
  std::array<Eigen::Matrix<double, 2, 4>, dot::kCellCount> jacobians;
  std::array<Eigen::Vector2d, dot::kCellCount> places;  // the dots' pixels at the fitted pose
  const RigidTransform camera_from_fitted = (to_transform(base_in_level) * base_from_camera).inverse();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!camera.project(camera_from_fitted * points[i], places[i])) return {};
  }
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
  CeilingCovariance information = CeilingCovariance::Zero(), along_u = information, along_v = information,
                    coupling = information;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector4d u_i = jacobians[i].row(0).transpose(), v_i = jacobians[i].row(1).transpose();
    information += u_i * u_i.transpose() + v_i * v_i.transpose();
    for (std::size_t k = 0; k < points.size(); ++k) {
      const Eigen::Vector4d u_k = jacobians[k].row(0).transpose(), v_k = jacobians[k].row(1).transpose();
      const Eigen::Vector2d apart = places[i] - places[k];
      const double same_u = grid_error_correlation(apart.x(), correlation_px);
      const double same_v = grid_error_correlation(apart.y(), correlation_px);
      along_u += same_u * u_i * u_k.transpose();
      along_v += same_v * v_i * v_k.transpose();
      // F(0,1): a dot's u and v errors go together; two dots share that at one place on both axes.
      coupling += same_u * same_v * (u_i * v_k.transpose() + v_i * u_k.transpose());
    }
  }
  const CeilingCovariance inverse = information.inverse();
  PixelErrorResponse response;
  response.along_u = inverse * along_u * inverse;
  response.along_v = inverse * along_v * inverse;
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
  sighting.pixel_error_response = pixel_error_response(sighting.base_in_marker, point_span, camera, base_from_camera,
                                                    config.grid_error_correlation_px);
  return true;
}

}  // namespace irloc::survey
