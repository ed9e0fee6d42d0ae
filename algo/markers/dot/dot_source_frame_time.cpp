// The dot source under a rolling shutter (algo/source/rolling_shutter.hpp): its pose at the
// frame's t_ns, the motion within the frame it is solved with, and the observations moved to t_ns.

#include <cmath>

#include "algo/markers/dot/dot_marker_source.hpp"
#include "algo/source/pose_motion_fit.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::dot {
namespace {

// Rolling shutter: refits with the points moved to t_ns from the last fit, until the pose they
// were moved with would move them less than kSettledPointChange from where the last fit moves them
// (moved_point_change over the whole readout: they depend on the pose only through the motion
// within the frame), a tenth of the goal's half millimetre; the pose moves by about half that at
// most (the dots' mean row time).
constexpr int kMaxMotionPasses = 3;
constexpr double kSettledPointChange = 5e-5;  // m

}  // namespace

DotPoseResult DotMarkerSource::solve_at_frame_time(const SourceInput& input, const DotPoseOptions& options) {
  const std::span<MarkerObservation> markers(markers_.begin(), markers_.size());
  line_time_ns_ = input.line_time_ns;
  limits_ = input.limits;
  motion_prior_ = frame_motion_prior(input);
  motion_.reset();
  own_motion_covariance_.setZero();
  plain_fit_.reset();
  if (line_time_ns_ <= 0) {
    last_plain_t_ns_.reset();
    return solve_dot_pose(markers, camera_, base_from_camera_, options);
  }

  for (std::size_t m = 0; m < markers_.size(); ++m) map_points_[m] = markers_[m].world;
  // From the track: its motion, and the pose it predicts for t_ns to move the points with.
  // Without one: the motion since the last pose, to this frame's plain fit when the last pose was
  // one too, else as each fit of this frame finds it.
  const bool from_track = input.motion && input.prior;
  const double readout = camera_.intrinsics().height * static_cast<double>(line_time_ns_) * 1e-9;  // s
  std::optional<RigidTransform> moved_with;
  if (from_track) {
    motion_ = input.motion;
    const double since = static_cast<double>(input.on.t_ns - input.prior->t_ns) * 1e-9;
    moved_with = pose_after(input.prior->world_from_base, since, *motion_);
    move_to_frame_time(*moved_with);
  }
  DotPoseResult pose = solve_dot_pose(markers, camera_, base_from_camera_, options);
  // A track whose motion or predicted pose this frame's dots refuse, or whose fit lies beyond the
  // fastest robot's reach from the last pose (a robot carried off, a track gone wrong): as with no
  // motion known.
  const bool track_refused =
      from_track && (!pose.fit.ok || beyond_reach(*input.prior, pose.fit.world_from_base, input.on.t_ns, input.limits));
  if (track_refused) {
    motion_.reset();
    for (std::size_t m = 0; m < markers_.size(); ++m) markers_[m].world = map_points_[m];
    pose = solve_dot_pose(markers, camera_, base_from_camera_, options);
  }
  // The first fit is the plain fit, at about its dots' mean row time. After a plain prior, the
  // motion between the two frames, once.
  const auto plain_delay_ns = std::llround(used_dots_time_and_height().first * 1e9);
  const bool from_plain_fits = !from_track && input.prior != nullptr && input.prior->plain;
  if (from_plain_fits && pose.fit.ok) motion_ = motion_after_plain_prior(input, pose.fit.world_from_base, plain_delay_ns);
  for (int pass = 0; pass < kMaxMotionPasses && pose.fit.ok && !track_refused; ++pass) {
    const RigidTransform& fitted = pose.fit.world_from_base;
    if (!from_plain_fits) motion_ = frame_motion(input, fitted, pass == 0 ? plain_delay_ns : 0);
    if (!motion_) break;
    if (moved_with && moved_point_change(fitted, *moved_with, *motion_, readout) < kSettledPointChange) break;
    moved_with = fitted;
    move_to_frame_time(fitted);
    pose = refit_dot_pose(markers, camera_, base_from_camera_, options, pose, fitted);
  }
  // No motion known (the first frame, after a gap): the frame's own dots, where they constrain it.
  if (!motion_ && pose.fit.ok) pose = solve_with_own_motion(options, pose);
  for (std::size_t m = 0; m < markers_.size(); ++m) markers_[m].world = map_points_[m];
  keep_dots_if_plain(input.on.t_ns, pose);
  return pose;
}

DotPoseResult DotMarkerSource::solve_with_own_motion(const DotPoseOptions& options, const DotPoseResult& plain) {
  const std::optional<PoseMotionFit> own = fit_motion_from_frame(plain.fit.world_from_base);
  if (!own) return plain;
  const std::span<MarkerObservation> markers(markers_.begin(), markers_.size());
  move_to_frame_time(own->world_from_base);
  DotPoseResult moved = refit_dot_pose(markers, camera_, base_from_camera_, options, plain, own->world_from_base);
  if (moved.fit.ok) {
    own_motion_covariance_ = own->motion_pose_covariance;
    plain_fit_ = plain.fit.world_from_base;
    return moved;
  }
  // The plain fit again, with its flags.
  motion_.reset();
  for (std::size_t m = 0; m < markers_.size(); ++m) markers_[m].world = map_points_[m];
  return solve_dot_pose(markers, camera_, base_from_camera_, options);
}

void DotMarkerSource::add_used_dots(DotSightings& sightings) const {
  for (std::size_t m = 0; m < markers_.size(); ++m) {
    if (!markers_[m].used) continue;
    for (std::size_t k = 0; k < markers_[m].dot_count && sightings.world.size() < sightings.kCapacity; ++k) {
      sightings.world.push_back(map_points_[m][k]);
      sightings.pixels.push_back(markers_[m].pixels[k]);
      sightings.times.push_back(row_time(markers_[m].pixels[k], line_time_ns_));
    }
  }
}

PoseMotionFit DotMarkerSource::fit_sightings(const DotSightings& sightings, const RigidTransform& plain) const {
  return fit_pose_and_motion({sightings.world.begin(), sightings.world.size()},
                             {sightings.pixels.begin(), sightings.pixels.size()},
                             {sightings.times.begin(), sightings.times.size()}, camera_, base_from_camera_, plain, dof_,
                             config_.min_pixel_sigma, motion_prior_);
}

std::optional<PoseMotionFit> DotMarkerSource::fit_motion_from_frame(const RigidTransform& plain) {
  DotSightings sightings;
  add_used_dots(sightings);
  const PoseMotionFit fit = fit_sightings(sightings, plain);
  if (!fit.ok) return std::nullopt;
  motion_ = fit.motion;
  return fit;
}

std::optional<FrameMotion> DotMarkerSource::motion_after_plain_prior(const SourceInput& input,
                                                                     const RigidTransform& plain,
                                                                     std::int64_t plain_delay_ns) const {
  if (!last_plain_t_ns_ || *last_plain_t_ns_ != input.prior->t_ns) return frame_motion(input, plain, plain_delay_ns);
  DotSightings sightings;
  const double back = static_cast<double>(*last_plain_t_ns_ - input.on.t_ns) * 1e-9;
  for (std::size_t k = 0; k < last_plain_dots_.world.size(); ++k) {
    sightings.world.push_back(last_plain_dots_.world[k]);
    sightings.pixels.push_back(last_plain_dots_.pixels[k]);
    sightings.times.push_back(back + last_plain_dots_.times[k]);
  }
  add_used_dots(sightings);
  const PoseMotionFit fit = fit_sightings(sightings, plain);
  if (!fit.ok) return frame_motion(input, plain, plain_delay_ns);
  return fit.motion;
}

void DotMarkerSource::keep_dots_if_plain(std::int64_t t_ns, const DotPoseResult& pose) {
  last_plain_t_ns_.reset();
  if (!pose.fit.ok || (motion_ && !plain_fit_)) return;
  last_plain_dots_.world.clear();
  last_plain_dots_.pixels.clear();
  last_plain_dots_.times.clear();
  add_used_dots(last_plain_dots_);
  last_plain_t_ns_ = t_ns;
}

void DotMarkerSource::move_to_frame_time(const RigidTransform& world_from_base) {
  for (std::size_t m = 0; m < markers_.size(); ++m) {
    MarkerObservation& marker = markers_[m];
    for (std::size_t k = 0; k < marker.dot_count; ++k) {
      marker.world[k] = point_seen_at_frame_time(map_points_[m][k], row_time(marker.pixels[k], line_time_ns_), *motion_,
                                                 world_from_base);
    }
  }
}

// The used dots' mean row time after t_ns, s, and their mean height, m (the ceiling they are on).
std::pair<double, double> DotMarkerSource::used_dots_time_and_height() const {
  double time = 0, height = 0;
  std::size_t dots = 0;
  for (const MarkerObservation& marker : markers_) {
    if (!marker.used) continue;
    for (std::size_t k = 0; k < marker.dot_count; ++k) {
      time += row_time(marker.pixels[k], line_time_ns_);
      height += marker.world[k].z();
    }
    dots += marker.dot_count;
  }
  return dots > 0 ? std::pair(time / static_cast<double>(dots), height / static_cast<double>(dots)) : std::pair(0.0, 0.0);
}

void DotMarkerSource::observations_to_frame_time(const RigidTransform& world_from_base, double ceiling_height,
                                                 SourceResult& result) const {
  for (PointObservation& point : result.observations) {
    const double plane_z = map_.find_dot_marker(point.landmark) != nullptr ? point.world.z() : ceiling_height;
    point.pixel = pixel_at_frame_time(point.pixel, row_time(point.pixel, line_time_ns_), *motion_, world_from_base,
                                      base_from_camera_, camera_, plane_z);
  }
}

}  // namespace irloc::dot
