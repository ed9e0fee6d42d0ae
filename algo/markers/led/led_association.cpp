#include "algo/markers/led/led_association.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include <Eigen/Geometry>

#include "algo/source/pose_motion_fit.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::led {
namespace {

// The motion within a frame fitted with the pose has three parameters (velocity x, y; yaw rate);
// it is fitted only where the matched LEDs leave the residual this many degrees of freedom, so
// that the residual still tests the association.
constexpr int kMotionParameters = 3;
constexpr int kMinFreedomWithMotion = 2;

double rotation_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cosine = 0.5 * ((a.transpose() * b).trace() - 1.0);
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

}  // namespace

LedAssociator::LedAssociator(const CameraModel& camera, const RigidTransform& base_from_camera, Dof dof,
                             const MarkerMap& map, const LedSourceConfig& config)
    : camera_(camera), base_from_camera_(base_from_camera), dof_(dof), map_(map), config_(config),
      neighbourhood_(map.led_landmarks, config.max_range, static_cast<std::size_t>(config.max_leds_in_range)),
      used_(kMaxLedDetections) {
  near_.reserve(neighbourhood_.densest());
  last_unseen_.reserve(neighbourhood_.densest());
  unseen_now_.reserve(neighbourhood_.densest());
  missed_.reserve(neighbourhood_.densest());
  unseen_.reserve(neighbourhood_.densest());
  refinement_.dof = dof;
  refinement_.loss = RobustLoss::huber;
  refinement_.loss_scale_px = config.loss_scale_px;
  refinement_.pixel_sigma = config.pixel_sigma;
  refinement_.stop_step_sigmas = RefinementOptions::kSourceStopStepSigmas;
}

LedAssociator::Scored LedAssociator::score(const RigidTransform& world_from_base, const LedDetectionList& detections,
                                           double gate_px, LedMatchList* matches, std::vector<int>* missed,
                                           const FrameMotion* motion) {
  Scored scored;
  if (matches != nullptr) matches->clear();
  if (missed != nullptr) missed->clear();
  std::fill(used_.begin(), used_.end(), 0);
  const RigidTransform world_from_camera = world_from_base * base_from_camera_;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  const double gate2 = gate_px * gate_px;
  const auto& intrinsics = camera_.intrinsics();
  neighbourhood_.near(world_from_camera.translation, near_);
  unseen_.clear();
  // Brightness x range^2 of the faintest matched LED (no match: every unseen LED would show).
  double faintest = std::numeric_limits<double>::infinity();
  for (const int l : near_) {
    const std::optional<PredictedLed> led = predict(l, world_from_base, world_from_camera, camera_from_world, motion);
    if (!led) continue;
    double nearest2 = gate2;
    const int nearest = nearest_unused(led->pixel, detections, nearest2);
    if (nearest >= 0) {
      used_[static_cast<std::size_t>(nearest)] = 1;
      ++scored.inliers;
      scored.cost += nearest2;
      if (matches != nullptr) matches->push_back({l, nearest});
      faintest = std::min(faintest, detections[static_cast<std::size_t>(nearest)].brightness * led->range * led->range);
    } else if (led->must_be_seen) {
      const double m = config_.edge_margin_px;
      if (led->pixel.x() > m && led->pixel.y() > m && led->pixel.x() < intrinsics.width - 1 - m &&
          led->pixel.y() < intrinsics.height - 1 - m) {
        unseen_.push_back({l, led->range, in_glare(led->pixel)});
      }
    }
  }
  // An unseen LED is missing where the faintest matched LED, moved to its range, would show, and
  // no glare hides it.
  for (const UnseenLed& led : unseen_) {
    if (led.hidden || faintest / (led.range * led.range) < config_.missing_brightness) continue;
    ++scored.missing;
    if (missed != nullptr) missed->push_back(led.landmark);
  }
  return scored;
}

std::optional<LedAssociator::PredictedLed> LedAssociator::predict(int l, const RigidTransform& world_from_base,
                                                                 const RigidTransform& world_from_camera,
                                                                 const RigidTransform& camera_from_world,
                                                                 const FrameMotion* motion) const {
  const LedLandmark& landmark = map_.led_landmarks[static_cast<std::size_t>(l)];
  const Eigen::Vector3d to_camera = world_from_camera.translation - landmark.position;
  PredictedLed led;
  led.range = to_camera.norm();
  if (led.range > config_.max_range || led.range < 1e-6) return std::nullopt;
  // Outside its emission cone an LED sends the camera nothing. The map's axis may be off the
  // LED's by cone_tolerance: near the cone's edge the LED may be seen or not.
  if (landmark.direction && landmark.half_angle) {
    const double off_axis = std::acos(std::clamp(landmark.direction->dot(to_camera) / led.range, -1.0, 1.0));
    if (off_axis > *landmark.half_angle + config_.cone_tolerance) return std::nullopt;
    led.must_be_seen = off_axis < *landmark.half_angle - config_.cone_tolerance;
  }
  if (!camera_.project(camera_from_world * landmark.position, led.pixel)) return std::nullopt;
  if (motion != nullptr) {
    const Eigen::Vector3d seen =
        point_seen_at_frame_time(landmark.position, led.pixel.y() * line_time_, *motion, world_from_base);
    if (!camera_.project(camera_from_world * seen, led.pixel)) return std::nullopt;
  }
  if (!camera_.in_image(led.pixel)) return std::nullopt;
  return led;
}

int LedAssociator::nearest_unused(const Eigen::Vector2d& pixel, const LedDetectionList& detections,
                                  double& distance2) const {
  int nearest = -1;
  for (std::size_t d = 0; d < detections.size(); ++d) {
    const double candidate2 = (detections[d].pixel - pixel).squaredNorm();
    if (!used_[d] && candidate2 < distance2) {
      distance2 = candidate2;
      nearest = static_cast<int>(d);
    }
  }
  return nearest;
}

bool LedAssociator::plausible(const RigidTransform& world_from_base) const {
  const double z = world_from_base.translation.z();
  if (z < config_.min_height || z > config_.max_height) return false;
  if (dof_ == Dof::full6) {
    const double tilt = std::acos(std::clamp(world_from_base.rotation(2, 2), -1.0, 1.0));
    if (tilt > config_.max_tilt) return false;
  }
  return true;
}

bool LedAssociator::in_glare(const Eigen::Vector2d& pixel) const {
  return std::any_of(glare_.begin(), glare_.end(), [&](const Eigen::AlignedBox2d& box) {
    return box.exteriorDistance(pixel) <= config_.edge_margin_px;
  });
}

bool LedAssociator::few_missing(int inliers, int missing) const {
  const int allowed = static_cast<int>(config_.max_missing_fraction * (inliers + missing));
  return missing <= std::max(config_.max_missing, allowed);
}

bool LedAssociator::residual_consistent(const PoseFit& fit, int matched, int motion_parameters) const {
  // Chi-square test of the squared residuals (2 per LED) against pixel_sigma, with the degrees
  // of freedom the fit leaves (2n - dof - motion parameters); its 0.999 quantile by Wilson and
  // Hilferty's form. A wrong association of more LEDs than the minimum leaves residuals of the
  // LED spacing.
  const int freedom = 2 * matched - static_cast<int>(dof_) - motion_parameters;
  if (freedom <= 0) return true;  // an exact fit: the residual says nothing
  const double k = freedom, z = 3.09;  // the standard normal's 0.999 quantile
  const double quantile = k * std::pow(1 - 2 / (9 * k) + z * std::sqrt(2 / (9 * k)), 3);
  const double squared = fit.rms_px * fit.rms_px * matched;
  return squared <= quantile * config_.pixel_sigma * config_.pixel_sigma;
}

bool LedAssociator::distinct(const RigidTransform& a, const RigidTransform& b) const {
  return (a.translation - b.translation).norm() > config_.distinct_position ||
         rotation_angle(a.rotation, b.rotation) > config_.distinct_angle;
}

bool LedAssociator::better(const Hypothesis& a, const Hypothesis& b) {
  if (a.inliers != b.inliers) return a.inliers > b.inliers;
  if (a.missing != b.missing) return a.missing < b.missing;
  return a.cost < b.cost;
}

void LedAssociator::consider(const RigidTransform& world_from_base, const LedDetectionList& detections) {
  if (!plausible(world_from_base)) return;
  const Scored scored = score(world_from_base, detections, config_.search_gate_px, nullptr, nullptr, known_motion());
  if (scored.inliers < min_leds() || !few_missing(scored.inliers, scored.missing)) return;
  const Hypothesis candidate{world_from_base, scored.inliers, scored.missing, scored.cost};
  for (Hypothesis& kept : kept_) {
    if (!distinct(kept.pose, candidate.pose)) {
      if (better(candidate, kept)) kept = candidate;
      return;
    }
  }
  if (kept_.push_back(candidate)) return;
  Hypothesis* worst = std::min_element(kept_.begin(), kept_.end(),
                                       [](const Hypothesis& a, const Hypothesis& b) { return better(b, a); });
  if (better(candidate, *worst)) *worst = candidate;
}

void LedAssociator::collect_fit_points(const LedMatchList& matches, const LedDetectionList& detections,
                                       const RigidTransform& world_from_base, const FrameMotion* motion) {
  fit_world_.clear();
  fit_pixels_.clear();
  fit_row_times_.clear();
  for (const LedMatch& match : matches) {
    const Eigen::Vector3d& world = map_.led_landmarks[static_cast<std::size_t>(match.landmark)].position;
    const Eigen::Vector2d& pixel = detections[static_cast<std::size_t>(match.detection)].pixel;
    const double dt = pixel.y() * line_time_;
    fit_world_.push_back(motion != nullptr ? point_seen_at_frame_time(world, dt, *motion, world_from_base) : world);
    fit_pixels_.push_back(pixel);
    fit_row_times_.push_back(dt);
  }
}

bool LedAssociator::refine_and_verify(const RigidTransform& start, const LedDetectionList& detections,
                                      LedMatchList& matches, LedAssociation& result) {
  RigidTransform pose = start;
  result.motion = line_time_ > 0 ? motion_ : std::nullopt;
  result.motion_fitted = false;
  result.motion_covariance.setZero();
  for (int pass = 0; pass < 2; ++pass) {
    const int matched = static_cast<int>(matches.size());
    if (matched < min_leds()) return false;
    if (line_time_ > 0 && !motion_) {
      // The motion within the frame unknown: fitted with the pose, where the residual still tests
      // the association; else a plain fit.
      result.motion.reset();
      result.motion_fitted = false;
      result.motion_covariance.setZero();
      if (2 * matched - static_cast<int>(dof_) - kMotionParameters >= kMinFreedomWithMotion) {
        collect_fit_points(matches, detections, pose, nullptr);
        const PoseMotionFit joint = fit_pose_and_motion(
            std::span<const Eigen::Vector3d>(fit_world_.begin(), fit_world_.size()),
            std::span<const Eigen::Vector2d>(fit_pixels_.begin(), fit_pixels_.size()),
            std::span<const double>(fit_row_times_.begin(), fit_row_times_.size()), camera_, base_from_camera_, pose,
            dof_, config_.pixel_sigma, motion_prior_);
        if (joint.ok) {
          result.motion = joint.motion;
          result.motion_fitted = true;
          if (motion_prior_) result.motion_covariance = joint.motion_pose_covariance;
          pose = joint.world_from_base;
        }
      }
    }
    const FrameMotion* motion = result.motion ? &*result.motion : nullptr;
    collect_fit_points(matches, detections, pose, motion);
    result.fit = refine_pose(std::span<const Eigen::Vector3d>(fit_world_.begin(), fit_world_.size()),
                             std::span<const Eigen::Vector2d>(fit_pixels_.begin(), fit_pixels_.size()), camera_,
                             base_from_camera_, pose, refinement_);
    if (!result.fit.ok) return false;
    pose = result.fit.world_from_base;
    if (pass == 0) {
      const Scored scored = score(pose, detections, config_.accept_gate_px, &matches, nullptr, motion);
      result.missing = scored.missing;
    }
  }
  result.matches = matches;
  const int matched = static_cast<int>(matches.size());
  return result.fit.rms_px <= config_.max_rms_px &&
         residual_consistent(result.fit, matched, result.motion_fitted ? kMotionParameters : 0) &&
         matched >= min_leds() && few_missing(matched, result.missing) && plausible(pose);
}

void LedAssociator::verify_distinct(const RigidTransform& start, const LedDetectionList& detections,
                                    LedMatchList& matches) {
  LedAssociation candidate;
  if (!refine_and_verify(start, detections, matches, candidate)) return;
  for (const LedAssociation& other : verified_) {
    if (!distinct(other.fit.world_from_base, candidate.fit.world_from_base)) return;
  }
  verified_.push_back(candidate);
}

bool LedAssociator::confirm_by_track(const RigidTransform& predicted, const LedDetectionList& detections,
                                     LedAssociation& result) {
  if (winner_ < 0 || result.outcome != LedOutcome::unconfirmed) return false;
  auto near_prediction = [&](const LedAssociation& association) {
    const RigidTransform& pose = association.fit.world_from_base;
    return (pose.translation - predicted.translation).norm() <= config_.track_max_jump &&
           rotation_angle(pose.rotation, predicted.rotation) <= config_.track_max_jump;
  };
  const LedAssociation& winner = verified_[static_cast<std::size_t>(winner_)];
  if (!near_prediction(winner) || std::count_if(verified_.begin(), verified_.end(), near_prediction) != 1) return false;
  accept(winner, result.margin, detections, result);
  return true;
}

void LedAssociator::collect_missed(const LedAssociation& association, const LedDetectionList& detections,
                                   std::vector<int>& missed, std::vector<int>& unseen) {
  score(association.fit.world_from_base, detections, config_.accept_gate_px, nullptr, &missed,
        association.motion ? &*association.motion : nullptr);
  std::sort(missed.begin(), missed.end());
  unseen.clear();
  for (const UnseenLed& led : unseen_) unseen.push_back(led.landmark);
  std::sort(unseen.begin(), unseen.end());
}

bool LedAssociator::leaves_detection_unexplained(const LedDetectionList& detections, const LedMatchList& matches) {
  Eigen::AlignedBox2d region;
  std::fill(used_.begin(), used_.end(), 0);
  for (const LedMatch& match : matches) {
    region.extend(detections[static_cast<std::size_t>(match.detection)].pixel);
    used_[static_cast<std::size_t>(match.detection)] = 1;
  }
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(config_.track_gate_px);
  region = Eigen::AlignedBox2d(region.min() - margin, region.max() + margin);
  for (std::size_t d = 0; d < detections.size(); ++d) {
    if (!used_[d] && region.contains(detections[d].pixel)) return true;
  }
  return false;
}

void LedAssociator::track(const RigidTransform& predicted, const LedDetectionList& detections, LedAssociation& result) {
  result = LedAssociation{};
  result.hypotheses = 1;
  // Each predicted LED takes the one detection within the tracking gate; a detection claimed by
  // two predictions, or a prediction with two detections in its gate, is left unmatched.
  LedMatchList matches;
  const RigidTransform camera_from_world = (predicted * base_from_camera_).inverse();
  const double gate2 = config_.track_gate_px * config_.track_gate_px;
  std::fill(used_.begin(), used_.end(), 0);
  const Eigen::Vector3d centre = (predicted * base_from_camera_).translation;
  neighbourhood_.near(centre, near_);
  for (const int l : near_) {
    const Eigen::Vector3d& position = map_.led_landmarks[static_cast<std::size_t>(l)].position;
    if ((position - centre).norm() > config_.max_range) continue;
    Eigen::Vector2d pixel;
    if (!camera_.project(camera_from_world * position, pixel)) continue;
    int found = -1, count = 0;
    for (std::size_t d = 0; d < detections.size(); ++d) {
      if ((detections[d].pixel - pixel).squaredNorm() < gate2) {
        found = static_cast<int>(d);
        ++count;
      }
    }
    if (count != 1) continue;
    ++used_[static_cast<std::size_t>(found)];
    matches.push_back({l, found});
  }
  LedMatchList unique;
  for (const LedMatch& match : matches) {
    if (used_[static_cast<std::size_t>(match.detection)] == 1) unique.push_back(match);
  }
  // Tracking has no competing hypothesis to beat: a prediction off by one LED spacing (a fast
  // turn between strided pairs) matches each LED to its neighbour's spot and leaves one end of the
  // row unexplained. So a tracked pose may miss no LED that the last pose saw, nor leave a
  // detection among its matched ones unexplained; otherwise the search, with its margin, decides.
  if (!refine_and_verify(predicted, detections, unique, result) || misses_a_seen_led(result, detections) ||
      leaves_detection_unexplained(detections, result.matches)) {
    result.ok = false;
    result.outcome = LedOutcome::track_lost;
    return;
  }
  const RigidTransform& pose = result.fit.world_from_base;
  if ((pose.translation - predicted.translation).norm() > config_.track_max_jump ||
      rotation_angle(pose.rotation, predicted.rotation) > config_.track_max_jump) {
    result.ok = false;
    result.outcome = LedOutcome::track_jumped;
    return;
  }
  result.ok = true;
  result.outcome = LedOutcome::found;
  last_unseen_.swap(unseen_now_);
}

bool LedAssociator::misses_a_seen_led(const LedAssociation& association, const LedDetectionList& detections) {
  collect_missed(association, detections, missed_, unseen_now_);
  return !std::includes(last_unseen_.begin(), last_unseen_.end(), missed_.begin(), missed_.end());
}

}  // namespace irloc::led
