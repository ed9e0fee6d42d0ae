#include "algo/survey/survey_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>

#include <Eigen/Geometry>

#include "algo/core/chi_square.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/survey/marker_dots.hpp"

namespace irloc::survey {
namespace {

CeilingPose node_pose(const DotMarker& marker) {
  return {marker.origin.x(), marker.origin.y(), marker.origin.z(), marker.yaw};
}

// A node known only through the weak prior.
CeilingCovariance weak_prior_covariance(const SurveyConfig& config) {
  return CeilingPose(config.prior_sigma_m, config.prior_sigma_m, config.prior_sigma_m, config.prior_sigma_yaw)
      .cwiseAbs2()
      .asDiagonal();
}

}  // namespace

CeilingPose SurveyEstimator::shared_error_variance() const { return graph_.shared_variance(); }

SurveyEstimator::SurveyEstimator(const CameraIntrinsics& camera, const RigidTransform& base_from_camera,
                                 const MarkerMap& map, const SurveyConfig& config)
    : camera_(camera),
      base_from_camera_(base_from_camera),
      config_(config),
      input_map_(map),
      graph_(map.dot_markers.size() + config.max_markers, config.max_markers, config),
      move_threshold_(chi_square_quantile(4 * config.move_window, config.move_false_alarm)),
      prior_move_threshold_(chi_square_quantile(4, config.move_false_alarm)),
      candidate_normal_quantile_(normal_upper_quantile(config.candidate_false_alarm)),
      poor_fit_normal_quantile_(normal_upper_quantile(config.poor_fit_false_alarm)),
      node_by_id_(dot::kMaxMarkerId + 1, -1),
      candidates_(config.max_candidates),
      repeated_share_(graph_.capacity()),
      marker_bias_(graph_.capacity()) {
  NodeState unused;
  unused.pitch = config.default_pitch;
  unused.radius = DotMarker{}.radius;
  unused.move_statistics.assign(static_cast<std::size_t>(config.move_window), 0.0);
  nodes_.assign(graph_.capacity(), unused);
  for (const DotMarker& marker : map.dot_markers) {
    std::optional<CeilingPose> prior_sigma;
    if (marker.sigma && !marker.fixed) {
      const CeilingPose floor(config.min_surveyed_sigma_m, config.min_surveyed_sigma_m, config.min_surveyed_sigma_m,
                              config.min_surveyed_sigma_yaw);
      prior_sigma = (config.surveyed_sigma_scale * *marker.sigma).cwiseMax(floor);
    }
    const int node = graph_.add_node(node_pose(marker), marker.fixed, prior_sigma);
    NodeState& mapped = state(node);
    mapped.holds_survey_prior = prior_sigma.has_value();
    if (!marker.fixed) {
      mapped.covariance =
          prior_sigma ? CeilingCovariance(prior_sigma->cwiseAbs2().asDiagonal()) : weak_prior_covariance(config);
    }
    mapped.id = marker.id;
    node_by_id_[static_cast<std::size_t>(marker.id)] = node;
    mapped.pitch = marker.pitch;
    mapped.radius = marker.radius;
  }
  graph_.solve(1);
}

int SurveyEstimator::node_of(int id) const {
  if (id < 0 || id > dot::kMaxMarkerId) return -1;
  return node_by_id_[static_cast<std::size_t>(id)];
}

bool SurveyEstimator::within_established_sigma(const CeilingCovariance& covariance) const {
  const double m2 = config_.established_sigma_m * config_.established_sigma_m;
  return covariance(0, 0) <= m2 && covariance(1, 1) <= m2 &&
         covariance(3, 3) <= config_.established_sigma_yaw * config_.established_sigma_yaw;
}

bool SurveyEstimator::established(int node) const {
  const auto n = static_cast<std::size_t>(node);
  if (graph_.fixed(node)) return true;
  // Settled: the last solve moved it less than its sigma (a surveyed marker that moved is pulled
  // across several frames by its sightings, and must not localize from a place it is leaving).
  const CeilingPose step = graph_.last_step(node);
  const CeilingCovariance& covariance = nodes_[n].covariance;
  const bool settled = step[0] * step[0] <= covariance(0, 0) && step[1] * step[1] <= covariance(1, 1) &&
                       step[3] * step[3] <= covariance(3, 3);
  return settled && graph_.sightings(node) >= config_.min_established_sightings && within_established_sigma(covariance);
}

// The marginal covariance of every marker seen in the frame, from the solve's factor.
void SurveyEstimator::update_covariances() {
  for (const FrameMarker& marker : frame_) {
    if (marker.node >= 0) graph_.factored_covariance(marker.node, state(marker.node).covariance);
  }
}

void SurveyEstimator::emit(const SurveyEvent& event) { events_.push_back(event); }

void SurveyEstimator::observe(const PointObservationList& observations) {
  ++report_.frames;
  collect_sightings(observations);
  update_graph();
  test_for_moves();
  graph_.solve(config_.iterations_per_frame);
  update_covariances();
  test_survey_priors();
  update_candidates();
}

// A marker surveyed before that its sightings have pulled off its map pose, beyond the move test's
// chi-square(4) quantile and the minimum move: it moved between the two runs.
void SurveyEstimator::test_survey_priors() {
  for (const FrameMarker& marker : frame_) {
    if (marker.node < 0 || !state(marker.node).holds_survey_prior) continue;
    if (graph_.sightings(marker.node) < config_.min_established_sightings) continue;
    if (graph_.prior_distance(marker.node) <= prior_move_threshold_) continue;
    const CeilingPose displacement = pose_difference(graph_.pose(marker.node), graph_.prior(marker.node));
    if (displacement.head<3>().norm() < config_.min_move_m && std::abs(displacement[3]) < config_.min_move_yaw) continue;
    state(marker.node).holds_survey_prior = false;
    emit({SurveyEvent::Kind::moved, state(marker.node).id, graph_.prior(marker.node).head<3>(),
          graph_.pose(marker.node).head<3>()});
    graph_.release_prior(marker.node);
  }
}

void SurveyEstimator::collect_sightings(const PointObservationList& observations) {
  frame_.clear();
  std::array<MarkerDots, kMaxMarkersPerFrame> groups;
  const std::size_t group_count = group_by_marker(observations, groups, report_.sightings_dropped);
  for (std::size_t g = 0; g < group_count; ++g) {
    const MarkerDots& group = groups[g];
    if (group.repeated) {
      ++report_.repeated_cells;
      continue;
    }
    FrameMarker marker;
    marker.node = node_of(group.id);
    if (marker.node >= 0 && state(marker.node).conflicted) continue;
    const double pitch = marker.node >= 0 ? state(marker.node).pitch : config_.default_pitch;
    if (!fit_sighting(std::span<const PointObservation>(group.dots.begin(), group.dots.size()), pitch, camera_,
                      base_from_camera_, config_, marker.sighting)) {
      ++report_.too_few_dots;
      continue;
    }
    ++report_.sightings;
    frame_.push_back(marker);
  }
  drop_poor_fits();
  measure_shared_errors();
}

// The dots' errors that sightings repeat, measured on this frame's markers: the share consecutive
// sightings repeat (repeated_share.hpp: the sightings of one line share it) and the pixel error
// every sighting of a marker repeats (marker_bias.hpp, per image axis), with each node's sightings'
// responses to it for the graph to turn it into a covariance of the node.
void SurveyEstimator::measure_shared_errors() {
  for (const FrameMarker& marker : frame_) {
    if (marker.node < 0) continue;
    repeated_share_.add(marker.node, marker.sighting, report_.frames);
    const Eigen::Matrix3d level_from_camera =
        Eigen::AngleAxisd(marker.sighting.base_in_marker[3], Eigen::Vector3d::UnitZ()) * base_from_camera_.rotation;
    marker_bias_.add(marker.node, marker.sighting, level_from_camera.topLeftCorner<2, 2>());
    graph_.add_marker_sighting(marker.node, marker.sighting.base_in_marker, marker.sighting.pixel_error_response);
  }
  graph_.set_repeated_share(repeated_share_.share());
  graph_.set_marker_pixel_error(marker_bias_.fixed_covariance());
}

RelativeSighting SurveyEstimator::pair_sighting(const MarkerSighting& a, const MarkerSighting& b) const {
  RelativeSighting relative = relative_sighting(a.base_in_marker, a.covariance, b.base_in_marker, b.covariance);
  const CeilingPose& base = a.base_in_marker;
  const Eigen::Vector3d camera = Eigen::Vector3d(base[0], base[1], base[2]) +
                                 Eigen::AngleAxisd(base[3], Eigen::Vector3d::UnitZ()) * base_from_camera_.translation;
  relative.camera_in_a = camera.head<2>();
  // A quarter of a pixel's footprint at the marker: within it a dot falls at the same sub-pixel place.
  relative.same_line_m = 0.25 * camera.norm() / camera_.intrinsics().fx;
  return relative;
}

// A sighting that fits its own dots far worse than the pooled pixel noise (chi-square over its
// redundancy at poor_fit_false_alarm: a dot clipped by the image's edge or merged with another)
// is not used: scaled by the pooled noise, its covariance would claim the precision of the
// others, and one such sighting kept a candidate's sightings disagreeing for good.
void SurveyEstimator::drop_poor_fits() {
  const double floor = config_.min_pixel_sigma * config_.min_pixel_sigma;
  std::size_t kept = 0;
  for (std::size_t k = 0; k < frame_.size(); ++k) {
    const MarkerSighting& sighting = frame_[k].sighting;
    const double variance = sighting.squared_residuals / sighting.redundancy;
    if (pixel_variance_ < 0) {
      pixel_variance_ = variance;
      pooled_sightings_ = 1;
    } else {
      const double reference = std::max(pixel_variance_, floor);
      const double limit = chi_square_quantile_at(static_cast<int>(sighting.redundancy), poor_fit_normal_quantile_);
      if (sighting.squared_residuals > limit * reference) {
        ++report_.poor_fits;
        continue;
      }
      // The pixel noise pooled over sightings (each alone has a few degrees of freedom and would
      // weight its own lucky frames up): the mean of the sightings so far, then a running mean
      // over the last 1 / smoothing (the first one alone would set the scale for a hundred).
      ++pooled_sightings_;
      const double weight = std::max(config_.pixel_noise_smoothing, 1.0 / pooled_sightings_);
      pixel_variance_ += weight * (variance - pixel_variance_);
    }
    frame_[kept++] = frame_[k];
  }
  while (frame_.size() > kept) frame_.pop_back();
  const double variance = std::max(pixel_variance_, floor);
  for (FrameMarker& marker : frame_) marker.sighting.covariance *= variance;
}

void SurveyEstimator::update_graph() {
  // The k markers of a frame share the robot's pose: their k (k - 1) / 2 pairs carry the
  // information of k - 1 independent relative sightings. With equal fits the exact information
  // (the robot's pose marginalized) is that of the pairs with each pair's scaled by 2 / k.
  int in_graph = 0;
  for (const FrameMarker& marker : frame_) in_graph += marker.node >= 0 ? 1 : 0;
  const double shared_pose_scale = in_graph > 2 ? 0.5 * in_graph : 1.0;
  for (std::size_t i = 0; i < frame_.size(); ++i) {
    for (std::size_t j = i + 1; j < frame_.size(); ++j) {
      FrameMarker* first = &frame_[i];
      FrameMarker* second = &frame_[j];
      if (first->node < 0 || second->node < 0) continue;
      if (first->node > second->node) std::swap(first, second);  // edges are stored low -> high
      const RelativeSighting relative = pair_sighting(first->sighting, second->sighting);
      if (established(first->node) && established(second->node)) {
        const double distance = graph_.sighting_distance(first->node, second->node, relative,
                                                         state(first->node).covariance, state(second->node).covariance);
        for (FrameMarker* marker : {first, second}) {
          if (marker->best_distance < 0 || distance < marker->best_distance) marker->best_distance = distance;
        }
        if (distance > config_.sighting_gate) {
          ++report_.gated_sightings;
          check_return(*first, *second);
          check_return(*second, *first);
          continue;
        }
      }
      if (!graph_.connect(first->node) || !graph_.connect(second->node)) {
        ++report_.graph_full;
        continue;
      }
      RelativeSighting scaled = relative;
      scaled.covariance *= shared_pose_scale;
      graph_.add_sighting(first->node, second->node, scaled, report_.frames);
    }
  }
}

void SurveyEstimator::check_return(FrameMarker& marker, const FrameMarker& partner) {
  NodeState& returning = state(marker.node);
  if (returning.returns < 0 || returning.conflicted) return;
  const RelativeSighting relative = relative_sighting(partner.sighting.base_in_marker, partner.sighting.covariance,
                                                      marker.sighting.base_in_marker, marker.sighting.covariance);
  const CeilingPose difference = pose_difference(compose(graph_.pose(partner.node), relative.b_in_a), returning.vacated);
  if (difference.head<3>().norm() > config_.candidate_radius_m || std::abs(difference[3]) > config_.candidate_radius_yaw) {
    return;
  }
  marker.returned = true;
  if (++returning.returns < config_.conflict_sightings) return;
  returning.conflicted = true;
  emit({SurveyEvent::Kind::conflict, returning.id, returning.vacated.head<3>(), graph_.pose(marker.node).head<3>()});
}

void SurveyEstimator::test_for_moves() {
  const auto window = static_cast<std::size_t>(config_.move_window);
  double worst_ratio = 1.0;
  FrameMarker* moved = nullptr;
  for (FrameMarker& marker : frame_) {
    if (marker.node < 0 || marker.best_distance < 0 || marker.returned || graph_.fixed(marker.node)) continue;
    NodeState& moving = state(marker.node);
    if (moving.conflicted) continue;
    int& count = moving.move_count;
    moving.move_statistics[static_cast<std::size_t>(count) % window] = marker.best_distance;
    ++count;
    if (static_cast<std::size_t>(count) < window) continue;
    double sum = 0;
    for (const double statistic : moving.move_statistics) sum += statistic;
    if (sum / move_threshold_ > worst_ratio) {
      worst_ratio = sum / move_threshold_;
      moved = &marker;
    }
  }
  if (moved == nullptr) return;

  // Its new place from a partner that agrees with the map in this frame (a fixed one first, else
  // the best agreeing); none: try again in a later frame.
  const FrameMarker* anchor = nullptr;
  for (const FrameMarker& marker : frame_) {
    if (&marker == moved || marker.node < 0 || !established(marker.node)) continue;
    const bool agrees = graph_.fixed(marker.node) ||
                        (marker.best_distance >= 0 && marker.best_distance <= config_.sighting_gate);
    if (!agrees) continue;
    if (anchor == nullptr || graph_.fixed(marker.node) ||
        (!graph_.fixed(anchor->node) && marker.best_distance < anchor->best_distance)) {
      anchor = &marker;
    }
  }
  if (anchor == nullptr) return;
  const RelativeSighting relative = relative_sighting(anchor->sighting.base_in_marker, anchor->sighting.covariance,
                                                      moved->sighting.base_in_marker, moved->sighting.covariance);
  const CeilingPose old_pose = graph_.pose(moved->node);
  const CeilingPose new_pose = compose(graph_.pose(anchor->node), relative.b_in_a);
  const CeilingPose displacement = pose_difference(new_pose, old_pose);
  if (displacement.head<3>().norm() < config_.min_move_m && std::abs(displacement[3]) < config_.min_move_yaw) return;
  graph_.restart_node(moved->node, new_pose);
  NodeState& restarted = state(moved->node);
  restarted.holds_survey_prior = false;
  restarted.covariance = weak_prior_covariance(config_);
  restarted.vacated = old_pose;
  restarted.returns = 0;
  for (const FrameMarker& marker : frame_) {
    if (marker.node >= 0) state(marker.node).move_count = 0;
  }
  emit({SurveyEvent::Kind::moved, restarted.id, old_pose.head<3>(), new_pose.head<3>()});
}

void SurveyEstimator::update_candidates() {
  for (const FrameMarker& marker : frame_) {
    if (marker.node >= 0) continue;
    // Placed through the established marker seen in the same frame that is surest of its place.
    const FrameMarker* anchor = nullptr;
    for (const FrameMarker& other : frame_) {
      if (other.node < 0 || !established(other.node)) continue;
      if (anchor == nullptr || state(other.node).covariance.trace() < state(anchor->node).covariance.trace()) {
        anchor = &other;
      }
    }
    if (anchor == nullptr) {
      ++report_.unanchored_sightings;
      continue;
    }
    const RelativeSighting relative = pair_sighting(anchor->sighting, marker.sighting);
    add_candidate_sighting(marker.sighting, anchor->node, relative);
  }
}

bool SurveyEstimator::near_another_marker(const CeilingPose& pose) const {
  for (std::size_t n = 0; n < graph_.size(); ++n) {
    if ((graph_.pose(static_cast<int>(n)).head<2>() - pose.head<2>()).norm() < config_.candidate_radius_m) return true;
  }
  return false;
}

void SurveyEstimator::add_candidate_sighting(const MarkerSighting& sighting, int anchor_node,
                                             const RelativeSighting& relative) {
  const int id = sighting.id;
  const CeilingPose& anchor_pose = graph_.pose(anchor_node);
  const CeilingPose pose = compose(anchor_pose, relative.b_in_a);
  const CeilingCovariance own = rotated_covariance(anchor_pose, relative.covariance);
  const CeilingCovariance anchor = anchor_share(anchor_pose, relative.b_in_a, state(anchor_node).covariance);
  MarkerCandidate* candidate = nullptr;
  MarkerCandidate* weakest = nullptr;
  for (MarkerCandidate& slot : candidates_) {
    if (slot.id == id) candidate = &slot;
    if (weakest == nullptr || slot.id < 0 || (weakest->id >= 0 && slot.sightings < weakest->sightings)) weakest = &slot;
  }
  if (candidate == nullptr) {
    // A full table gives way only to replace a one-off.
    if (weakest == nullptr || (weakest->id >= 0 && weakest->sightings > 2)) {
      ++report_.candidates_full;
      return;
    }
    *weakest = MarkerCandidate{};
    weakest->id = id;
    weakest->reference = pose;
    weakest->anchor_covariance = anchor;
    weakest->view_min = weakest->view_max = sighting.base_in_marker.head<2>();
    candidate = weakest;
  }
  if (candidate->conflict) return;
  const auto near = [&](const CeilingPose& mean) {
    const CeilingPose difference = pose_difference(pose, mean);
    return difference.head<3>().norm() < config_.candidate_radius_m &&
           std::abs(difference[3]) < config_.candidate_radius_yaw;
  };
  if (candidate->sightings == 0 || near(candidate->mean())) {
    candidate->add_sighting(pose, own, anchor, sighting.base_in_marker.head<2>(), anchor_node, relative);
  } else if (candidate->other_sightings == 0 || near(candidate->other_mean)) {
    candidate->add_other_sighting(pose);
  }
  if (candidate->sightings >= config_.conflict_sightings && candidate->other_sightings >= config_.conflict_sightings) {
    candidate->conflict = true;
    emit({SurveyEvent::Kind::conflict, id, candidate->mean().head<3>(), candidate->other_mean.head<3>()});
    return;
  }
  if (candidate->other_sightings >= config_.conflict_sightings) return;
  if (learn(*candidate)) *candidate = MarkerCandidate{};
}

// The evidence that makes a candidate a marker: enough sightings from robot positions apart, that
// agree with each other, placing it within the established sigmas, and not on another marker.
bool SurveyEstimator::learn(MarkerCandidate& candidate) {
  if (candidate.sightings < config_.min_candidate_sightings) return false;
  if ((candidate.view_max - candidate.view_min).norm() < config_.min_candidate_baseline_m) return false;
  const CeilingPose mean_offset = candidate.information.ldlt().solve(candidate.information_offset);
  const double spread = candidate.weighted_squares - mean_offset.dot(candidate.information_offset);
  if (spread > chi_square_quantile_at(4 * (candidate.sightings - 1), candidate_normal_quantile_)) return false;
  const CeilingCovariance covariance = candidate.covariance();
  if (!within_established_sigma(covariance)) return false;
  const CeilingPose place = candidate.mean();
  if (near_another_marker(place)) {
    ++report_.misread_candidates;
    return false;
  }
  // A weak prior at that place, and its sightings as edges from their anchors: as the graph
  // refines the anchors, the learned marker follows them (all connected: room checked first).
  std::size_t connections = 1;
  for (std::size_t k = 0; k < candidate.kept.size(); ++k) {
    const int anchor = candidate.kept[k].anchor;
    bool counted = graph_.connected(anchor);
    for (std::size_t j = 0; j < k && !counted; ++j) counted = candidate.kept[j].anchor == anchor;
    if (!counted) ++connections;
  }
  if (connections > graph_.free_connections()) {
    ++report_.graph_full;
    return false;
  }
  const int node = graph_.add_node(place, false);
  if (node < 0) {
    ++report_.graph_full;
    return false;
  }
  const auto n = static_cast<std::size_t>(node);
  graph_.connect(node);
  for (const MarkerCandidate::Anchored& kept : candidate.kept) graph_.connect(kept.anchor);
  nodes_[n].id = candidate.id;
  node_by_id_[static_cast<std::size_t>(candidate.id)] = node;
  nodes_[n].covariance = covariance;  // until a solve gives its marginal
  nodes_[n].learned = true;
  // Their frames are past: together one visit.
  for (const MarkerCandidate::Anchored& kept : candidate.kept) graph_.add_sighting(kept.anchor, node, kept.sighting, 0);
  emit({SurveyEvent::Kind::added, candidate.id, Eigen::Vector3d::Zero(), place.head<3>()});
  return true;
}

DotMarker SurveyEstimator::marker_entry(int node) const {
  const auto n = static_cast<std::size_t>(node);
  DotMarker marker;
  marker.id = nodes_[n].id;
  marker.origin = graph_.pose(node).head<3>();
  marker.yaw = graph_.pose(node)[3];
  marker.pitch = nodes_[n].pitch;
  marker.radius = nodes_[n].radius;
  marker.fixed = graph_.fixed(node);
  return marker;
}

void SurveyEstimator::established_markers(std::vector<DotMarker>& markers) const {
  markers.clear();
  for (std::size_t n = 0; n < graph_.size(); ++n) {
    const int node = static_cast<int>(n);
    if (nodes_[n].conflicted || !established(node)) continue;
    DotMarker marker = marker_entry(node);
    if (!graph_.fixed(node)) marker.sigma = nodes_[n].covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
    markers.push_back(marker);
  }
}

bool SurveyEstimator::estimate(int id, DotMarker& marker) const {
  const int node = node_of(id);
  if (node < 0 || state(node).conflicted) return false;
  marker = marker_entry(node);
  return true;
}

MarkerMap SurveyEstimator::estimated_map() const {
  MarkerMap map = input_map_;
  map.dot_markers.clear();
  const std::vector<CeilingCovariance> covariances = graph_.covariances();
  for (std::size_t n = 0; n < graph_.size(); ++n) {
    const int node = static_cast<int>(n);
    if (nodes_[n].conflicted || (nodes_[n].learned && !established(node))) continue;
    if (graph_.fixed(node)) {
      map.dot_markers.push_back(input_map_.dot_markers[n]);  // copied unchanged (the map's markers are the first nodes)
      continue;
    }
    DotMarker marker = marker_entry(node);
    marker.sigma = covariances[n].diagonal().cwiseMax(0.0).cwiseSqrt();
    map.dot_markers.push_back(marker);
  }
  return map;
}

}  // namespace irloc::survey
