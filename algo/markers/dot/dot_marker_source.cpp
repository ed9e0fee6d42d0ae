#include "algo/markers/dot/dot_marker_source.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "algo/markers/dot/cell_contrast.hpp"
#include "algo/markers/dot/cell_decoder.hpp"
#include "algo/markers/dot/direction_dots.hpp"
#include "algo/markers/dot/dot_outcome.hpp"
#include "algo/markers/dot/grey_level_model.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::dot {
namespace {

constexpr int kMaxThresholdDoublings = 2;
// One relabelling for a threshold of its own, one per doubling.
static_assert(kMaxThresholdDoublings + 1 <= static_cast<int>(PairPass::kMaxRelabels));

double mean_pitch(const std::vector<DotMarker>& markers) {
  if (markers.empty()) return 0.04;
  double sum = 0;
  for (const DotMarker& marker : markers) sum += marker.pitch;
  return sum / static_cast<double>(markers.size());
}

double max_pitch(const std::vector<DotMarker>& markers) {
  double largest = 0.04;
  for (const DotMarker& marker : markers) largest = std::max(largest, marker.pitch);
  return largest;
}

double mean_radius(const std::vector<DotMarker>& markers) {
  if (markers.empty()) return 0.01;
  double sum = 0;
  for (const DotMarker& marker : markers) sum += marker.radius;
  return sum / static_cast<double>(markers.size());
}

// The camera's distance to the ceiling: configured, or the mean marker height above the camera of
// a level robot standing on z = 0.
double ceiling_distance(const DotSourceConfig& config, const std::vector<DotMarker>& markers,
                        const RigidTransform& base_from_camera) {
  if (config.ceiling_distance > 0) return config.ceiling_distance;
  if (markers.empty()) return 2.5;
  double sum = 0;
  for (const DotMarker& marker : markers) sum += marker.origin.z();
  const double distance = sum / static_cast<double>(markers.size()) - base_from_camera.translation.z();
  if (!(distance > 0)) throw std::invalid_argument("dot path: the mapped dot markers are not above the camera");
  return distance;
}

}  // namespace

DotMarkerSource::DotMarkerSource(const SourceSetup& setup, const DotSourceConfig& config)
    : config_(config),
      camera_(setup.camera),
      base_from_camera_(setup.base_from_camera),
      dof_(setup.dof),
      map_(setup.map),
      // Up (W's z of a level robot) seen from the camera.
      plane_(base_from_camera_.rotation.transpose() * Eigen::Vector3d::UnitZ(),
             ceiling_distance(config, map_.dot_markers, base_from_camera_)),
      selector_(config_, camera_, plane_,
                std::numbers::pi * std::pow(setup.camera.fx * mean_radius(map_.dot_markers) / plane_.distance(), 2)),
      track_identifier_(camera_, base_from_camera_, map_) {
  expected_diagonal_ = 3.0 * std::numbers::sqrt2 * mean_pitch(map_.dot_markers);
  link_distance_ = config_.link_factor * 3.0 * max_pitch(map_.dot_markers);
  const double radius_px = setup.camera.fx * mean_radius(map_.dot_markers) / plane_.distance();
  window_radius_ = std::clamp(static_cast<int>(std::lround(0.5 * radius_px)), 1, 3);
}

void DotMarkerSource::observe(const DecodedCells& decoded, const DotMarker* mapped,
                              MarkerObservation& observation) const {
  observation = MarkerObservation{};
  observation.id = decoded.id;
  double log_grey = 0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    const std::int16_t index = decoded.candidate_of_cell[static_cast<std::size_t>(cell)];
    if (index < 0) continue;
    const DotCandidate& candidate = candidates_[static_cast<std::size_t>(index)];
    const std::size_t k = observation.dot_count++;
    observation.cells[k] = static_cast<std::uint8_t>(cell);
    observation.world[k] = mapped != nullptr ? cell_in_world(*mapped, cell) : Eigen::Vector3d::Zero();
    observation.pixels[k] = candidate.pixel;
    observation.centre_pixel += candidate.pixel;
    log_grey += std::log(std::max(dot_posterior(config_.grey_levels, candidate.mean_intensity), 1e-12));
  }
  observation.centre_pixel /= observation.dot_count;
  observation.evidence.grey = std::exp(log_grey / observation.dot_count);
}

void DotMarkerSource::report_every_marker(SourceResult& result) const {
  for (const MarkerObservationList* list : {&markers_, &unmapped_markers_}) {
    for (const MarkerObservation& marker : *list) {
      for (std::size_t i = 0; i < marker.dot_count; ++i) {
        result.observations.push_back({marker.id, marker.cells[i], marker.pixels[i], marker.world[i]});
      }
    }
  }
}

void DotMarkerSource::decode_groups(const SourceInput& input, const GrayImageView& on, const GrayImageView& off) {
  bool predicted = false;
  for (DotGroup& group : groups_) {
    DirectionDots direction;
    if (!find_direction_dots(candidates_, config_, expected_diagonal_, group, direction)) {
      if (!predicted) {  // once a frame, where a group needs it
        const double readout = camera_.intrinsics().height * static_cast<double>(input.line_time_ns) * 1e-9;
        track_identifier_.predict(predict_from_track(input, readout));
        predicted = true;
      }
      identify_by_track(group, on, off);  // the whole group: nothing was dropped
      continue;
    }
    DecodedCells decoded;
    if (!decode_cells(candidates_, group, direction, config_.snap_tolerance, decoded)) {
      ++report_.impossible_layout;
      continue;
    }
    const CellContrast contrast = measure_cell_contrast(decoded, plane_, camera_, on, off, window_radius_);
    if (contrast.margin < config_.min_cell_margin) {
      ++report_.low_cell_margin;
      continue;
    }
    const DotMarker* mapped = map_.find_dot_marker(decoded.id);
    if (mapped == nullptr) ++report_.unknown_ids;
    if (mapped == nullptr && !config_.observe_every_marker) continue;
    MarkerObservation observation;
    observe(decoded, mapped, observation);
    observation.evidence.margin = contrast.margin;
    if (!(mapped != nullptr ? markers_ : unmapped_markers_).push_back(observation)) ++report_.markers_dropped;
  }
}

void DotMarkerSource::identify_by_track(const DotGroup& group, const GrayImageView& on, const GrayImageView& off) {
  TrackMatch match;
  const auto decoded_already = [&](int id) {
    return std::any_of(markers_.begin(), markers_.end(),
                       [&](const MarkerObservation& marker) { return marker.id == id; });
  };
  if (!track_identifier_.identify(candidates_, group, match) || decoded_already(match.decoded.id)) {
    ++report_.no_direction_dots;
    return;
  }
  const CellContrast contrast = measure_cell_contrast_at(match.cell_pixels, cells_from_id(match.decoded.id),
                                                         match.predicted, on, off, window_radius_);
  if (contrast.margin < config_.min_cell_margin) {
    ++report_.low_cell_margin;
    return;
  }
  MarkerObservation observation;
  observe(match.decoded, match.marker, observation);
  observation.evidence.margin = contrast.margin;
  observation.identified_by_track = true;
  if (!markers_.push_back(observation)) {
    ++report_.markers_dropped;
    return;
  }
  ++report_.identified_by_track;
}

void DotMarkerSource::process(const SourceInput& input, SourceResult& result) {
  result.clear(SourceKind::dot);
  StageClock clock;
  clock.start(result.times);
  report_ = DotFrameReport{};
  markers_.clear();
  unmapped_markers_.clear();
  if (input.off == nullptr) {
    result.set_outcome(DotOutcome::no_off_frame);
    return;
  }
  const GrayImageView& on = input.on.image;
  const GrayImageView& off = input.off->image;

  find_candidates(*input.pair, off, clock, result.times);

  report_.groups = group_candidates(candidates_, link_distance_, groups_);
  clock.mark(result.times, "grouping");

  decode_groups(input, on, off);
  report_.markers_decoded = static_cast<std::uint32_t>(markers_.size());
  if (config_.observe_every_marker) report_every_marker(result);
  clock.mark(result.times, "decoding");
  if (markers_.empty()) {
    result.set_outcome(DotOutcome::no_marker_decoded);
    return;
  }

  const DotPoseOptions options = pose_options();
  const DotPoseResult pose = solve_at_frame_time(input, options);
  clock.mark(result.times, "pose");
  if (!pose.fit.ok) {
    result.set_outcome(DotOutcome::pose_fit_failed);
    return;
  }

  rate_pose(pose);
  clock.mark(result.times, "confidence");
  fill_result(pose, options.refinement, result);
  if (report_.confidence < config_.confidence_floor) {
    result.set_outcome(DotOutcome::low_confidence);
    return;
  }
  result.ok = true;
  const bool track_identified = std::any_of(markers_.begin(), markers_.end(), [](const MarkerObservation& marker) {
    return marker.used && marker.identified_by_track;
  });
  result.set_outcome(track_identified ? DotOutcome::found_with_track_identified : DotOutcome::found);
}

void DotMarkerSource::find_candidates(PairPass& pair, const GrayImageView& off, StageClock& clock, StageClock::Times& times) {
  // The shared noise estimate of the pair, with this source's own threshold settings (the
  // Localizer labels the shared pass with the same ones, so normally nothing is relabelled).
  report_.threshold = config_.threshold > 0 ? config_.threshold
                                            : pair.analysis().noise.threshold(config_.threshold_sigmas, config_.min_threshold);
  // Noise far above the estimate (shot noise under a bright window, a sparkling lamp) floods the
  // blob and candidate lists; rather than lose the dots among the overflow, the pair is labelled
  // again at twice the threshold, at most kMaxThresholdDoublings times (bounded work).
  for (int doubling = 0;; ++doubling) {
    if (pair.analysis().threshold != report_.threshold) {
      if (!pair.relabel(report_.threshold)) {  // not reached (static_assert above): keep the last labelling
        report_.threshold = pair.analysis().threshold;
        break;
      }
      clock.mark(times, "front_end");
    }
    report_.blobs = pair.analysis().blob_counters;
    report_.candidates = selector_.select(pair.analysis().blobs, off, candidates_);
    clock.mark(times, "candidates");
    const bool overflow = report_.blobs.blobs_dropped > 0 || report_.blobs.runs_dropped > 0 || report_.candidates.dropped > 0;
    if (!overflow || doubling == kMaxThresholdDoublings) break;
    report_.threshold *= 2;
    ++report_.threshold_doublings;
  }
}

DotPoseOptions DotMarkerSource::pose_options() const {
  DotPoseOptions options;
  options.refinement.dof = dof_;
  options.refinement.loss = RobustLoss::huber;
  options.refinement.loss_scale_px = config_.refine_loss_scale_px;
  options.refinement.stop_step_sigmas = RefinementOptions::kSourceStopStepSigmas;
  options.marker_gate_px = config_.marker_gate_px;
  return options;
}

void DotMarkerSource::rate_pose(const DotPoseResult& pose) {
  StaticVector<MarkerEvidence, kMaxMarkersInView> evidence;
  for (const MarkerObservation& marker : markers_) {
    if (marker.used) evidence.push_back(marker.evidence);
  }
  report_.markers_used = static_cast<std::uint32_t>(pose.markers_used);
  report_.rms_px = pose.fit.rms_px;
  report_.confidence = pose_confidence(config_, {evidence.begin(), evidence.size()}, pose.fit.rms_px);
}

// A surveyed map's markers carry their own sigma, and the pose inherits it. To first order the fit
// registers the used dots in the floor plane: marker i's error (shift e_i, turn d_i about its
// origin O_i) moves its dots, which turns the fit by sum_i (R_i x e_i + d_i Q_i) / S (r_k: dot k
// from the centroid of all dots, R_i = sum of r_k over the marker, Q_i = sum r_k . (w_k - O_i),
// S = sum |r_k|^2) and shifts it by the dot-weighted mean of the e_i; the turn moves the robot by
// its distance from the centroid. Only on the parameters the dof leaves free.
void DotMarkerSource::add_map_uncertainty(const Eigen::Vector3d& base_position, PoseCovariance& covariance) const {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double dots = 0;
  bool any_sigma = false;
  for (const MarkerObservation& marker : markers_) {
    const DotMarker* mapped = marker.used ? map_.find_dot_marker(marker.id) : nullptr;
    if (mapped == nullptr) continue;
    any_sigma = any_sigma || mapped->sigma.has_value();
    for (std::size_t k = 0; k < marker.dot_count; ++k) centroid += marker.world[k].head<2>();
    dots += marker.dot_count;
  }
  if (!any_sigma || dots == 0) return;
  centroid /= dots;
  double spread = 0, turn = 0, shift = 0, height = 0;
  for (const MarkerObservation& marker : markers_) {
    const DotMarker* mapped = marker.used ? map_.find_dot_marker(marker.id) : nullptr;
    if (mapped == nullptr) continue;
    const Eigen::Vector4d sigma = mapped->sigma.value_or(Eigen::Vector4d::Zero());
    const double axis_variance = 0.5 * (sigma[0] * sigma[0] + sigma[1] * sigma[1]);
    Eigen::Vector2d lever_sum = Eigen::Vector2d::Zero();
    double own_turn = 0;
    for (std::size_t k = 0; k < marker.dot_count; ++k) {
      const Eigen::Vector2d r = marker.world[k].head<2>() - centroid;
      spread += r.squaredNorm();
      lever_sum += r;
      own_turn += r.dot(marker.world[k].head<2>() - mapped->origin.head<2>());
    }
    turn += lever_sum.squaredNorm() * axis_variance + own_turn * own_turn * sigma[3] * sigma[3];
    shift += marker.dot_count * marker.dot_count * axis_variance;
    height += marker.dot_count * marker.dot_count * sigma[2] * sigma[2];
  }
  const double yaw_variance = spread > 0 ? turn / (spread * spread) : 0;
  const double arm = (base_position.head<2>() - centroid).squaredNorm();
  const double horizontal = shift / (dots * dots) + yaw_variance * arm;
  const double added[6] = {horizontal, horizontal, height / (dots * dots), 0, 0, yaw_variance};
  for (int k = 0; k < 6; ++k) {
    if (covariance(k, k) > 0) covariance(k, k) += added[k];
  }
}

void DotMarkerSource::fill_result(const DotPoseResult& pose, const RefinementOptions& refinement,
                                  SourceResult& result) const {
  result.world_from_base = pose.fit.world_from_base;
  // The refinement's covariance assumes refinement.pixel_sigma; the fit's own residuals say what
  // the pixel noise was in this frame (the a-posteriori variance factor cost / (2 n - p)), so the
  // covariance is rescaled to it: a blurred or noisy frame reports a larger uncertainty.
  std::size_t dots = 0;
  for (const MarkerObservation& marker : markers_) dots += marker.used ? marker.dot_count : 0;
  const auto redundancy = static_cast<double>(2 * dots) - static_cast<double>(static_cast<int>(dof_));
  const double pixel_variance = redundancy > 0 ? pose.fit.cost / redundancy : 0;
  const double floor = config_.min_pixel_sigma * config_.min_pixel_sigma;
  result.covariance = pose.fit.covariance * (std::max(pixel_variance, floor) /
                                             (refinement.pixel_sigma * refinement.pixel_sigma));
  add_map_uncertainty(result.world_from_base.translation, result.covariance);
  result.marker_id = markers_[static_cast<std::size_t>(pose.reference_marker)].id;
  result.confidence = report_.confidence;
  result.rms_px = pose.fit.rms_px;
  if (!config_.observe_every_marker) {  // else already reported, every marker
    for (const MarkerObservation& marker : markers_) {
      if (!marker.used) continue;
      for (std::size_t i = 0; i < marker.dot_count; ++i) {
        result.observations.push_back({marker.id, marker.cells[i], marker.pixels[i], marker.world[i]});
      }
    }
  }
  if (line_time_ns_ <= 0) return;
  // Rolling shutter: the pose is the one at t_ns. With the motion from the poses before the frame,
  // so are the observations' pixels. With the motion fitted to the frame's own dots (a drive's
  // first frame), the covariance holds that motion's uncertainty, the observations stay at their
  // rows' times and the track takes the plain fit: the next frame's motion, fitted to both
  // frames' dots, revises this pose (Localizer::revised_previous). With the motion unknown, the
  // covariance allows for the fastest robot's motion (rolling_shutter.hpp).
  const auto [mean_time, ceiling_height] = used_dots_time_and_height();
  if (plain_fit_) {
    result.covariance += own_motion_covariance_;
    result.pose_delay_ns = std::llround(mean_time * 1e9);
    result.plain_fit = plain_fit_;
    result.plain_fit_delay_ns = result.pose_delay_ns;
  } else if (motion_) {
    observations_to_frame_time(result.world_from_base, ceiling_height, result);
    result.motion_from_track = motion_;
  } else {
    add_unknown_motion(mean_time, limits_, result.covariance);
    result.pose_delay_ns = std::llround(mean_time * 1e9);
  }
}

}  // namespace irloc::dot
