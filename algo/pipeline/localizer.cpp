#include "algo/pipeline/localizer.hpp"

#include <algorithm>
#include <utility>

namespace irloc {
namespace {

PoseEstimate square_pose(const StrobePair& pair, const SquareDetection& square) {
  PoseEstimate estimate;
  estimate.seq = pair.on.seq;
  estimate.t_ns = pair.on.t_ns;
  estimate.source = SourceKind::square;
  if (!square.found()) return estimate;
  const RollPitchYaw rpy = rpy_from_rotation(square.world_from_base.rotation);
  estimate.ok = true;
  estimate.x = square.world_from_base.translation.x();
  estimate.y = square.world_from_base.translation.y();
  estimate.z = square.world_from_base.translation.z();
  estimate.yaw = rpy.yaw;
  estimate.confidence = square.confidence;
  return estimate;
}

}  // namespace

Localizer::Localizer(LocalizerSetup setup) : setup_(std::move(setup)) {
  if (!setup_.map.dot_markers.empty()) {
    dot_path_ = std::make_unique<dot::DotPath>(setup_.camera, setup_.mount, setup_.dof, setup_.map, setup_.dot);
  }
  if (setup_.map.square_markers.size() == 1 && setup_.dof != Dof::full6) {
    square_path_ = std::make_unique<SquareDetector>(setup_.camera, setup_.mount, setup_.dof,
                                                    setup_.map.square_markers.front(), setup_.square);
  }
}

PoseEstimate Localizer::process(const StrobePair& pair) {
  stage_times_.clear();
  PoseEstimate estimate;
  estimate.seq = pair.on.seq;
  estimate.t_ns = pair.on.t_ns;
  if (dot_path_) estimate = dot_path_->process(pair, stage_times_);
  if (!dot_path_ && square_path_) estimate.source = SourceKind::square;  // the only path: name it in `none` rows too
  last_square_ = SquareDetection{};
  if (!square_path_ || !pair.off) return estimate;

  StageClock clock;
  StageClock::Times square_time;
  clock.start(square_time);
  last_square_ = square_path_->detect(pair.on.image, pair.off->image);
  clock.mark(square_time, "square");
  stage_times_.push_back(square_time[0]);

  const PoseEstimate square = square_pose(pair, last_square_);
  if (!square.ok) return estimate;
  if (!estimate.ok) return square;
  return fuse(estimate, square);
}

// Both paths found a pose: their weighted mean, or none when they disagree.
PoseEstimate Localizer::fuse(const PoseEstimate& dot_pose, const PoseEstimate& square) const {
  PoseEstimate fused = square;
  fused.ok = false;
  fused.source = SourceKind::fused;
  fused.marker_id = dot_pose.marker_id;

  // The dot path's uncertainty from the dots it used: pixel noise (its fit's RMS, at least 0.3 px)
  // times each dot's footprint on the ceiling, from the square path's table scaled to the dot's
  // height.
  const CeilingPlaneMap& plane = square_path_->plane();
  const double camera_z = setup_.mount.translation().z() + dot_pose.z;
  StaticVector<double, dot::kMaxMarkersInView * dot::kCellCount> footprints;
  StaticVector<Eigen::Vector2d, dot::kMaxMarkersInView * dot::kCellCount> points;
  for (const dot::MarkerObservation& marker : dot_path_->last_markers()) {
    if (!marker.used) continue;
    for (std::size_t i = 0; i < marker.dot_count; ++i) {
      const Eigen::Vector2d& pixel = marker.pixels[i];
      const int x = std::clamp(static_cast<int>(pixel.x() + 0.5), 0, plane.width() - 1);
      const int y = std::clamp(static_cast<int>(pixel.y() + 0.5), 0, plane.height() - 1);
      const double footprint = plane.metres_per_pixel(x, y);
      if (footprint <= 0) continue;
      footprints.push_back(footprint * (marker.world[i].z() - camera_z) / plane.ceiling_above_camera());
      points.push_back(marker.world[i].head<2>());
    }
  }
  LevelPose dot_level{dot_pose.x, dot_pose.y, dot_pose.z, dot_pose.yaw, 0, 0};
  point_fit_uncertainty({footprints.begin(), footprints.size()}, {points.begin(), points.size()},
                        std::max(dot_path_->last_report().rms_px, 0.3), dot_level);
  const LevelPose square_level{square.x, square.y, square.z, square.yaw, last_square_.position_sigma,
                               last_square_.yaw_sigma};
  LevelPose result;
  if (!fuse_level_poses(dot_level, square_level, setup_.fusion, result)) return fused;
  fused.ok = true;
  fused.x = result.x;
  fused.y = result.y;
  fused.z = result.z;
  fused.yaw = result.yaw;
  fused.confidence = std::max(dot_pose.confidence, square.confidence);
  return fused;
}

}  // namespace irloc
