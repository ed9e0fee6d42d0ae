#include "algo/markers/led/led_landmark_source.hpp"

#include <cmath>

#include "algo/geometry/pose_refinement.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::led {

LedLandmarkSource::LedLandmarkSource(const SourceSetup& setup, const LedSourceConfig& config)
    : config_(config),
      camera_(setup.camera),
      base_from_camera_(setup.base_from_camera),
      dof_(setup.dof),
      map_(setup.map),
      detector_(setup.camera.width, setup.camera.height, setup.pixel_bits, config),
      associator_(camera_, setup.base_from_camera, setup.dof, setup.map, config) {}

void LedLandmarkSource::restart() {
  track_length_ = 0;
  has_pose_ = false;
  last_t_ns_ = previous_t_ns_ = 0;
  last_hypotheses_ = 0;
  last_pose_ = previous_pose_ = RigidTransform{};
  association_ = LedAssociation{};
  associator_.restart();
}

RigidTransform LedLandmarkSource::predicted_pose(std::int64_t t_ns) const {
  if (track_length_ < 2 || last_t_ns_ <= previous_t_ns_) return last_pose_;
  // Constant velocity in the pose parameters, from the last two poses.
  const double ratio = static_cast<double>(t_ns - last_t_ns_) / static_cast<double>(last_t_ns_ - previous_t_ns_);
  const PoseParameters last = parameters_from_pose(last_pose_);
  PoseParameters step = last - parameters_from_pose(previous_pose_);
  for (int angle = 3; angle < 6; ++angle) step[angle] = wrap_angle(step[angle]);
  return pose_from_parameters(last + ratio * step);
}

void LedLandmarkSource::process(const SourceInput& input, SourceResult& result) {
  result.clear(SourceKind::led);
  clock_.start(result.times);
  detector_.detect(input.on.image, input.off != nullptr ? &input.off->image : nullptr, detections_, glare_, counters_);
  associator_.set_glare(glare_);
  bearings_.clear();
  for (const LedDetection& detection : detections_) {
    Eigen::Vector3d bearing;
    bearings_.push_back(camera_.unproject(detection.pixel, bearing) ? bearing : Eigen::Vector3d::Zero());
  }
  clock_.mark(result.times, "led detect");

  const double since_last = static_cast<double>(input.on.t_ns - last_t_ns_) * 1e-9;
  if (track_length_ > 0 && (since_last < 0 || since_last > config_.track_timeout)) track_length_ = 0;
  association_.ok = false;
  last_hypotheses_ = 0;
  associator_.set_rolling_shutter(static_cast<double>(input.line_time_ns) * 1e-9, motion_within_frame(input),
                                  input.motion_prior);
  if (track_length_ > 0) associator_.track(predicted_pose(input.on.t_ns), detections_, association_);
  if (!association_.ok) {
    search(input.on.t_ns, since_last, input.limits);
  }
  if (association_.ok && !certain_enough(association_.fit.covariance)) {
    association_.ok = false;
    association_.outcome = LedOutcome::too_uncertain;
  }
  clock_.mark(result.times, "led pose");

  result.set_outcome(association_.outcome);
  if (!association_.ok) {
    track_length_ = 0;
    return;
  }
  const PoseFit& fit = association_.fit;
  result.ok = true;
  result.world_from_base = fit.world_from_base;
  result.covariance = fit.covariance;
  result.rms_px = fit.rms_px;
  const double matched = static_cast<double>(association_.matches.size());
  result.confidence = matched / (matched + association_.missing) *
                      std::exp(-0.5 * fit.rms_px * fit.rms_px / (config_.max_rms_px * config_.max_rms_px));
  for (const LedMatch& match : association_.matches) {
    result.observations.push_back({match.landmark, 0, detections_[static_cast<std::size_t>(match.detection)].pixel,
                                   map_.led_landmarks[static_cast<std::size_t>(match.landmark)].position});
  }
  if (input.line_time_ns > 0) pose_at_frame_time(input, result);
  previous_pose_ = last_pose_;
  previous_t_ns_ = last_t_ns_;
  last_pose_ = result.world_from_base;
  last_t_ns_ = input.on.t_ns;
  ++track_length_;
  has_pose_ = true;
}

void LedLandmarkSource::search(std::int64_t t_ns, double since_last, const MotionLimits& limits) {
  associator_.search(detections_, bearings_, association_);
  last_hypotheses_ = association_.hypotheses;
  // A minimal set that the track predicts: the evidence tracking itself accepts, while the last
  // pose is recent (the track may have failed on a turn beyond its pixel gate, or on an LED that
  // left the view).
  if (has_pose_ && since_last >= 0 && since_last <= config_.track_timeout) {
    associator_.confirm_by_track(predicted_pose(t_ns), detections_, association_);
  }
  if (association_.ok && !within_reach(association_.fit.world_from_base, t_ns, limits)) {
    association_.ok = false;
    association_.outcome = LedOutcome::out_of_reach;
  }
}

std::optional<FrameMotion> LedLandmarkSource::motion_within_frame(const SourceInput& input) const {
  if (input.line_time_ns <= 0) return std::nullopt;
  if (input.motion) return input.motion;
  // The source's own track: the motion between its last two poses, while recent.
  if (track_length_ < 2 || input.on.t_ns - last_t_ns_ > kMaxTrackGapNs) return std::nullopt;
  const PosePrior previous{previous_pose_, previous_t_ns_, false};
  return motion_since(&previous, last_pose_, last_t_ns_, kMaxTrackGapNs);
}

void LedLandmarkSource::pose_at_frame_time(const SourceInput& input, SourceResult& result) const {
  if (!association_.motion) {  // a plain fit to the row-skewed centres
    move_fit_to_frame_time(input, camera_, base_from_camera_, dof_, result);
    return;
  }
  // The fit is the pose at t_ns already; the observations follow. A motion fitted from this
  // frame's LEDs alone is uncertain as the motion unknown is (rolling_shutter.hpp); one fitted with
  // the motion before a gap as its prior, as the fit says.
  observations_to_frame_time(input.line_time_ns, *association_.motion, camera_, base_from_camera_, result);
  if (!association_.motion_fitted) result.motion_from_track = association_.motion;
  if (association_.motion_fitted && input.motion_prior) {
    result.covariance += association_.motion_covariance;
  } else if (association_.motion_fitted) {
    double mean_time = 0;
    for (const PointObservation& point : result.observations) mean_time += row_time(point.pixel, input.line_time_ns);
    add_unknown_motion(mean_time / static_cast<double>(result.observations.size()), input.limits, result.covariance);
  }
}

bool LedLandmarkSource::certain_enough(const Eigen::Matrix<double, 6, 6>& covariance) const {
  // The robot needs x, y and yaw; z, roll and pitch are what a forward camera on one wall observes
  // worst under dof 6 (height and pitch trade off), and the robot does not use them.
  const double horizontal_sigma = std::sqrt(covariance(0, 0) + covariance(1, 1));
  return horizontal_sigma <= config_.max_position_sigma && std::sqrt(covariance(5, 5)) <= config_.max_yaw_sigma;
}

bool LedLandmarkSource::within_reach(const RigidTransform& pose, std::int64_t t_ns, const MotionLimits& limits) const {
  const double dt = static_cast<double>(t_ns - last_t_ns_) * 1e-9;
  if (!has_pose_ || dt < 0 || dt > config_.reach_window) return true;
  const double yaw_change = std::abs(wrap_angle(rpy_from_rotation(pose.rotation).yaw -
                                                rpy_from_rotation(last_pose_.rotation).yaw));
  return (pose.translation - last_pose_.translation).norm() <= limits.speed * dt + config_.track_max_jump &&
         yaw_change <= limits.yaw_rate * dt + config_.track_max_jump;
}

}  // namespace irloc::led
