#include "algo/markers/dot/track_identification.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "algo/geometry/pose.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::dot {
namespace {

// The step of the numeric Jacobian of a pixel by the pose's parameters, m and rad.
constexpr double kJacobianStep = 1e-5;
// A row time's pixel and the row it is in depend on each other: two passes settle it (a pass
// moves the pixel by its motion over the change of its row's time: well under 0.01 px).
constexpr int kRowTimePasses = 2;
constexpr std::size_t kYaw = 5;

RigidTransform camera_from_world(const RigidTransform& world_from_base, const RigidTransform& base_from_camera) {
  return (world_from_base * base_from_camera).inverse();
}

// The pose with parameter k of (x, y, z, roll, pitch, yaw) moved by step.
RigidTransform moved_parameter(const RigidTransform& pose, int k, double step) {
  RigidTransform moved = pose;
  if (k < 3) {
    moved.translation[k] += step;
    return moved;
  }
  const RollPitchYaw rpy = rpy_from_rotation(pose.rotation);
  moved.rotation = rotation_from_rpy(rpy.roll + (k == 3 ? step : 0), rpy.pitch + (k == 4 ? step : 0),
                                     rpy.yaw + (k == 5 ? step : 0));
  return moved;
}

// The grid point of `cell` with the marker turned by `quarters` about its centre and shifted by
// `shift` grid steps.
Eigen::Vector2d moved_cell(int cell, int quarters, const Eigen::Vector2d& shift) {
  const Eigen::Vector2d centre(1.5, 1.5);
  Eigen::Vector2d offset(cell_column(cell) - centre.x(), cell_row(cell) - centre.y());
  for (int q = 0; q < quarters; ++q) offset = Eigen::Vector2d(-offset.y(), offset.x());
  return centre + offset + shift;
}

// Whether `seen` lies within kGateSigmas standard deviations of `predicted` (Mahalanobis, under the
// predicted pixel's information matrix).
bool within_gate(const Eigen::Vector2d& seen, const Eigen::Vector2d& predicted, const Eigen::Matrix2d& information) {
  const Eigen::Vector2d residual = seen - predicted;
  return residual.dot(information * residual) <= TrackIdentifier::kGateSigmas * TrackIdentifier::kGateSigmas;
}

}  // namespace

std::optional<TrackPrediction> predict_from_track(const SourceInput& input, double readout_s) {
  if (!input.motion || input.prior == nullptr || input.on.t_ns < input.prior->t_ns) return std::nullopt;
  const double since = static_cast<double>(input.on.t_ns - input.prior->t_ns) * 1e-9;
  TrackPrediction prediction;
  prediction.world_from_base = pose_after(input.prior->world_from_base, since, *input.motion);
  prediction.motion = *input.motion;
  prediction.line_time_ns = input.line_time_ns;
  prediction.covariance = input.prior->covariance;
  // Over the time to the frame's last row: the motion's uncertainty, and a change of the motion at
  // the rates the robot may change it (fastest_motion_change).
  const double span = since + readout_s;
  const MotionChangeRates rates = fastest_motion_change(input.limits);
  const double position_drift = 0.5 * rates.acceleration * span * span;
  const double yaw_drift = 0.5 * rates.yaw_acceleration * span * span;
  const double position_variance = span * span * input.motion_velocity_variance + position_drift * position_drift;
  prediction.covariance(0, 0) += position_variance;
  prediction.covariance(1, 1) += position_variance;
  prediction.covariance(kYaw, kYaw) += span * span * input.motion_yaw_rate_variance + yaw_drift * yaw_drift;
  return prediction;
}

TrackIdentifier::TrackIdentifier(const CameraModel& camera, const RigidTransform& base_from_camera,
                                 const MarkerMap& map)
    : camera_(camera), base_from_camera_(base_from_camera), map_(map) {}

bool TrackIdentifier::predicted_pixel(const Eigen::Vector3d& world, Eigen::Vector2d& pixel) const {
  if (!camera_.project(camera_from_world(prediction_.world_from_base, base_from_camera_) * world, pixel)) return false;
  if (prediction_.line_time_ns <= 0) return true;
  for (int pass = 0; pass < kRowTimePasses; ++pass) {
    const RigidTransform at_row =
        pose_after(prediction_.world_from_base, row_time(pixel, prediction_.line_time_ns), prediction_.motion);
    if (!camera_.project(camera_from_world(at_row, base_from_camera_) * world, pixel)) return false;
  }
  return true;
}

Eigen::Matrix2d TrackIdentifier::pixel_information(const Eigen::Vector3d& world) const {
  const PoseCovariance& covariance = prediction_.covariance;
  Eigen::Matrix<double, 2, 6> jacobian = Eigen::Matrix<double, 2, 6>::Zero();
  Eigen::Vector2d base_pixel;
  // A pixel the model cannot differentiate gates nothing out (every dot within it: a refusal).
  if (!camera_.project(camera_from_world(prediction_.world_from_base, base_from_camera_) * world, base_pixel)) {
    return Eigen::Matrix2d::Zero();
  }
  for (int k = 0; k < 6; ++k) {
    if (!(covariance(k, k) > 0)) continue;
    const RigidTransform moved = moved_parameter(prediction_.world_from_base, k, kJacobianStep);
    Eigen::Vector2d moved_pixel;
    if (!camera_.project(camera_from_world(moved, base_from_camera_) * world, moved_pixel)) {
      return Eigen::Matrix2d::Zero();
    }
    jacobian.col(k) = (moved_pixel - base_pixel) / kJacobianStep;
  }
  const Eigen::Matrix2d pixel_covariance = jacobian * covariance * jacobian.transpose() +
                                           kCentroidSigmaPx * kCentroidSigmaPx * Eigen::Matrix2d::Identity();
  return pixel_covariance.inverse();
}

void TrackIdentifier::predict_marker(const DotMarker& marker, double depth) {
  PredictedMarker near;
  near.marker = &marker;
  near.populated = cells_from_id(marker.id);
  near.dot_radius_px = camera_.intrinsics().fx * marker.radius / depth;
  for (int cell = 0; cell < kCellCount; ++cell) {
    const auto c = static_cast<std::size_t>(cell);
    const Eigen::Vector3d world = cell_in_world(marker, cell);
    if (!predicted_pixel(world, near.pixels[c])) continue;
    near.predicted = static_cast<CellMask>(near.predicted | (1u << cell));
    if ((near.populated >> cell) & 1u) {
      near.information[c] = pixel_information(world);
    }
  }
  if (!near_.push_back(near)) too_many_ = true;
}

void TrackIdentifier::predict(const std::optional<TrackPrediction>& prediction) {
  near_.clear();
  too_many_ = false;
  widest_dot_radius_px_ = 0;
  if (!prediction) return;
  prediction_ = *prediction;
  const RigidTransform from_world = camera_from_world(prediction_.world_from_base, base_from_camera_);
  const auto& intrinsics = camera_.intrinsics();
  for (const DotMarker& marker : map_.dot_markers) {
    const Eigen::Vector3d centre = from_world * grid_in_world(marker, Eigen::Vector2d(1.5, 1.5));
    Eigen::Vector2d pixel;
    if (!(centre.z() > 0) || !camera_.project(centre, pixel)) continue;
    // Near: within the marker's diagonal of the image (and what the frame's motion moves it by).
    const double reach = intrinsics.fx * 3 * std::numbers::sqrt2 * marker.pitch / centre.z();
    if (pixel.x() < -reach || pixel.y() < -reach || pixel.x() > intrinsics.width + reach ||
        pixel.y() > intrinsics.height + reach) {
      continue;
    }
    predict_marker(marker, centre.z());
  }
  for (const PredictedMarker& near : near_) widest_dot_radius_px_ = std::max(widest_dot_radius_px_, near.dot_radius_px);
}

bool TrackIdentifier::inside_by(const Eigen::Vector2d& pixel, double margin) const {
  const auto& intrinsics = camera_.intrinsics();
  return pixel.x() >= margin - 0.5 && pixel.y() >= margin - 0.5 && pixel.x() <= intrinsics.width - 0.5 - margin &&
         pixel.y() <= intrinsics.height - 0.5 - margin;
}

bool TrackIdentifier::fits_elsewhere(const DotCandidateList& candidates, const DotGroup& group,
                                     const PredictedMarker& near) const {
  // Each group dot near some dot of the moved marker (not necessarily a different one: a doubt is
  // a refusal).
  const auto fits = [&](int quarters, const Eigen::Vector2d& shift) {
    StaticVector<Eigen::Vector2d, kCellCount> dots;
    StaticVector<const Eigen::Matrix2d*, kCellCount> informations;  // of the cell each came from
    for (int cell = 0; cell < kCellCount; ++cell) {
      Eigen::Vector2d pixel;
      if (((near.populated >> cell) & 1u) && ((near.predicted >> cell) & 1u) &&
          predicted_pixel(grid_in_world(*near.marker, moved_cell(cell, quarters, shift)), pixel)) {
        dots.push_back(pixel);
        informations.push_back(&near.information[static_cast<std::size_t>(cell)]);
      }
    }
    return std::all_of(group.members.begin(), group.members.end(), [&](std::uint8_t member) {
      for (std::size_t k = 0; k < dots.size(); ++k) {
        if (within_gate(candidates[member].pixel, dots[k], *informations[k])) return true;
      }
      return false;
    });
  };
  for (int dx = -1; dx <= 1; ++dx) {
    for (int dy = -1; dy <= 1; ++dy) {
      if ((dx != 0 || dy != 0) && fits(0, Eigen::Vector2d(dx, dy))) return true;
    }
  }
  for (int quarters = 1; quarters < 4; ++quarters) {
    if (fits(quarters, Eigen::Vector2d::Zero())) return true;
  }
  return false;
}

bool TrackIdentifier::identify(const DotCandidateList& candidates, const DotGroup& group, TrackMatch& match) const {
  if (too_many_ || near_.empty()) return false;
  // A dot within its radius (and a pixel) of the edge may be cut: its centroid is biased, so it is
  // neither matched nor used.
  DotGroup whole;
  for (const std::uint8_t member : group.members) {
    if (inside_by(candidates[member].pixel, widest_dot_radius_px_ + kEdgeTolerancePx)) whole.members.push_back(member);
  }
  if (whole.members.size() < static_cast<std::size_t>(kMinMatchedDots)) return false;
  std::array<std::int16_t, kCellCount> candidate_of_cell;
  candidate_of_cell.fill(-1);
  CellMask matched = 0;
  std::size_t owner = near_.size();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  for (const std::uint8_t member : whole.members) {
    const Eigen::Vector2d& seen = candidates[member].pixel;
    int hits = 0, hit_cell = -1;
    std::size_t hit_marker = 0;
    for (std::size_t m = 0; m < near_.size(); ++m) {
      for (int cell = 0; cell < kCellCount; ++cell) {
        const auto c = static_cast<std::size_t>(cell);
        if (!((near_[m].populated & near_[m].predicted) >> cell & 1u)) continue;
        if (!within_gate(seen, near_[m].pixels[c], near_[m].information[c])) continue;
        ++hits;
        hit_marker = m;
        hit_cell = cell;
      }
    }
    if (hits != 1 || (owner != near_.size() && hit_marker != owner) || ((matched >> hit_cell) & 1u)) return false;
    owner = hit_marker;
    matched = static_cast<CellMask>(matched | (1u << hit_cell));
    candidate_of_cell[static_cast<std::size_t>(hit_cell)] = member;
    offset += seen - near_[owner].pixels[static_cast<std::size_t>(hit_cell)];
  }
  offset /= static_cast<double>(whole.members.size());
  const PredictedMarker& near = near_[owner];
  // Each dot the group lacks is off the image or cut by its edge, where the matched dots put it.
  for (int cell = 0; cell < kCellCount; ++cell) {
    const bool lacked = ((near.populated >> cell) & 1u) && !((matched >> cell) & 1u);
    if (lacked && ((near.predicted >> cell) & 1u) &&
        inside_by(near.pixels[static_cast<std::size_t>(cell)] + offset, near.dot_radius_px + kEdgeTolerancePx)) {
      return false;
    }
  }
  if (fits_elsewhere(candidates, whole, near)) return false;

  match = TrackMatch{};
  match.marker = near.marker;
  match.decoded.cells = matched;
  match.decoded.id = near.marker->id;
  match.decoded.candidate_of_cell = candidate_of_cell;
  for (std::size_t c = 0; c < near.pixels.size(); ++c) match.cell_pixels[c] = near.pixels[c] + offset;
  match.predicted = near.predicted;
  return true;
}

}  // namespace irloc::dot
