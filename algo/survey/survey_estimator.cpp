#include "algo/survey/survey_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::survey {
namespace {

CeilingPose node_pose(const DotMarker& marker) {
  return {marker.origin.x(), marker.origin.y(), marker.origin.z(), marker.yaw};
}

// The standard normal's upper quantile by bisection on erfc (start-up only).
double normal_upper_quantile(double tail) {
  double low = 0, high = 40;
  for (int i = 0; i < 200; ++i) {
    const double middle = (low + high) / 2;
    (0.5 * std::erfc(middle / std::sqrt(2.0)) > tail ? low : high) = middle;
  }
  return (low + high) / 2;
}

}  // namespace

double chi_square_quantile(int degrees, double tail) {
  const double k = degrees;
  const double z = normal_upper_quantile(tail);
  const double spread = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - spread + z * std::sqrt(spread), 3);
}

SurveyEstimator::SurveyEstimator(const CameraIntrinsics& camera, const RigidTransform& base_from_camera,
                                 const MarkerMap& map, const SurveyConfig& config)
    : camera_(camera),
      base_from_camera_(base_from_camera),
      config_(config),
      input_map_(map),
      graph_(std::max(config.max_markers, map.dot_markers.size()), config),
      move_threshold_(chi_square_quantile(4 * config.move_window, config.move_false_alarm)),
      prior_move_threshold_(chi_square_quantile(4, config.move_false_alarm)),
      node_ids_(graph_.capacity(), -1),
      node_pitch_(graph_.capacity(), config.default_pitch),
      node_radius_(graph_.capacity(), DotMarker{}.radius),
      move_statistics_(graph_.capacity() * static_cast<std::size_t>(config.move_window), 0.0),
      move_count_(graph_.capacity(), 0),
      vacated_(graph_.capacity(), CeilingPose::Zero()),
      returns_(graph_.capacity(), -1),
      conflicted_(graph_.capacity(), false),
      holds_survey_prior_(graph_.capacity(), false),
      candidates_(config.max_candidates) {
  for (const DotMarker& marker : map.dot_markers) {
    std::optional<CeilingPose> prior_sigma;
    if (marker.sigma && !marker.fixed) {
      const CeilingPose floor(config.min_surveyed_sigma_m, config.min_surveyed_sigma_m, config.min_surveyed_sigma_m,
                              config.min_surveyed_sigma_yaw);
      prior_sigma = (config.surveyed_sigma_scale * *marker.sigma).cwiseMax(floor);
    }
    const int node = graph_.add_node(node_pose(marker), marker.fixed, prior_sigma);
    holds_survey_prior_[static_cast<std::size_t>(node)] = prior_sigma.has_value();
    node_ids_[static_cast<std::size_t>(node)] = marker.id;
    node_pitch_[static_cast<std::size_t>(node)] = marker.pitch;
    node_radius_[static_cast<std::size_t>(node)] = marker.radius;
  }
  graph_.solve(1);
}

int SurveyEstimator::node_of(int id) const {
  for (std::size_t node = 0; node < graph_.size(); ++node) {
    if (node_ids_[node] == id) return static_cast<int>(node);
  }
  return -1;
}

bool SurveyEstimator::established(int node) const {
  return graph_.fixed(node) || graph_.sightings(node) >= config_.established_sightings;
}

void SurveyEstimator::emit(const SurveyEvent& event) { events_.push_back(event); }

void SurveyEstimator::observe(const PointObservationList& observations) {
  ++report_.frames;
  collect_sightings(observations);
  update_graph();
  test_for_moves();
  graph_.solve(config_.iterations_per_frame);
  test_survey_priors();
  update_candidates();
}

// A marker surveyed before that its sightings have pulled off its map pose, beyond the move test's
// chi-square(4) quantile and the minimum move: it moved between the two runs.
void SurveyEstimator::test_survey_priors() {
  for (const FrameMarker& marker : frame_) {
    if (marker.node < 0 || !holds_survey_prior_[static_cast<std::size_t>(marker.node)]) continue;
    if (graph_.sightings(marker.node) < config_.established_sightings) continue;
    if (graph_.prior_distance(marker.node) <= prior_move_threshold_) continue;
    const CeilingPose displacement = pose_difference(graph_.pose(marker.node), graph_.prior(marker.node));
    if (displacement.head<3>().norm() < config_.min_move_m && std::abs(displacement[3]) < config_.min_move_yaw) continue;
    holds_survey_prior_[static_cast<std::size_t>(marker.node)] = false;
    emit({SurveyEvent::Kind::moved, node_ids_[static_cast<std::size_t>(marker.node)], graph_.prior(marker.node).head<3>(),
          graph_.pose(marker.node).head<3>()});
    graph_.release_prior(marker.node);
  }
}

void SurveyEstimator::collect_sightings(const PointObservationList& observations) {
  frame_.clear();
  struct Group {
    int id = -1;
    std::uint32_t cells = 0;
    bool repeated = false;
    StaticVector<PointObservation, dot::kCellCount> dots;
  };
  std::array<Group, kMaxMarkersPerFrame> groups;
  std::size_t group_count = 0;
  for (const PointObservation& observation : observations) {
    std::size_t g = 0;
    while (g < group_count && groups[g].id != observation.landmark) ++g;
    if (g == group_count) {
      if (group_count == kMaxMarkersPerFrame) {
        ++report_.sightings_dropped;
        continue;
      }
      groups[group_count++].id = observation.landmark;
    }
    Group& group = groups[g];
    const std::uint32_t bit = 1u << (observation.point & 31);
    if (observation.point < 0 || observation.point >= dot::kCellCount || (group.cells & bit) != 0 ||
        !group.dots.push_back(observation)) {
      group.repeated = true;
      continue;
    }
    group.cells |= bit;
  }
  for (std::size_t g = 0; g < group_count; ++g) {
    const Group& group = groups[g];
    if (group.repeated) {
      ++report_.repeated_cells;
      continue;
    }
    FrameMarker marker;
    marker.node = node_of(group.id);
    if (marker.node >= 0 && conflicted_[static_cast<std::size_t>(marker.node)]) continue;
    const double pitch = marker.node >= 0 ? node_pitch_[static_cast<std::size_t>(marker.node)] : config_.default_pitch;
    if (!fit_sighting(std::span<const PointObservation>(group.dots.begin(), group.dots.size()), pitch, camera_,
                      base_from_camera_, config_, marker.sighting)) {
      ++report_.too_few_dots;
      continue;
    }
    ++report_.sightings;
    frame_.push_back(marker);
  }
  // The pixel noise pooled over sightings (each alone has a few degrees of freedom and would
  // weight its own lucky frames up), then every sighting's covariance scaled to it.
  for (const FrameMarker& marker : frame_) {
    const double variance = marker.sighting.squared_residuals / marker.sighting.redundancy;
    pixel_variance_ = pixel_variance_ < 0 ? variance
                                          : pixel_variance_ + config_.pixel_noise_smoothing * (variance - pixel_variance_);
  }
  const double variance = std::max(pixel_variance_, config_.min_pixel_sigma * config_.min_pixel_sigma);
  for (FrameMarker& marker : frame_) marker.sighting.covariance *= variance;
}

void SurveyEstimator::update_graph() {
  for (std::size_t i = 0; i < frame_.size(); ++i) {
    for (std::size_t j = i + 1; j < frame_.size(); ++j) {
      FrameMarker* first = &frame_[i];
      FrameMarker* second = &frame_[j];
      if (first->node < 0 || second->node < 0) continue;
      if (first->node > second->node) std::swap(first, second);  // edges are stored low -> high
      const RelativeSighting relative =
          relative_sighting(first->sighting.base_in_marker, first->sighting.covariance,
                            second->sighting.base_in_marker, second->sighting.covariance);
      if (established(first->node) && established(second->node)) {
        const double distance = graph_.sighting_distance(first->node, second->node, relative);
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
      graph_.add_sighting(first->node, second->node, relative);
    }
  }
}

void SurveyEstimator::check_return(FrameMarker& marker, const FrameMarker& partner) {
  const auto node = static_cast<std::size_t>(marker.node);
  if (returns_[node] < 0 || conflicted_[node]) return;
  const RelativeSighting relative = relative_sighting(partner.sighting.base_in_marker, partner.sighting.covariance,
                                                      marker.sighting.base_in_marker, marker.sighting.covariance);
  const CeilingPose difference = pose_difference(compose(graph_.pose(partner.node), relative.b_in_a), vacated_[node]);
  if (difference.head<3>().norm() > config_.candidate_radius_m || std::abs(difference[3]) > config_.candidate_radius_yaw) {
    return;
  }
  marker.returned = true;
  if (++returns_[node] < config_.min_candidate_sightings / 2) return;
  conflicted_[node] = true;
  emit({SurveyEvent::Kind::conflict, node_ids_[node], vacated_[node].head<3>(), graph_.pose(marker.node).head<3>()});
}

void SurveyEstimator::test_for_moves() {
  const auto window = static_cast<std::size_t>(config_.move_window);
  double worst_ratio = 1.0;
  FrameMarker* moved = nullptr;
  for (FrameMarker& marker : frame_) {
    if (marker.node < 0 || marker.best_distance < 0 || marker.returned || graph_.fixed(marker.node)) continue;
    if (conflicted_[static_cast<std::size_t>(marker.node)]) continue;
    const auto node = static_cast<std::size_t>(marker.node);
    int& count = move_count_[node];
    move_statistics_[node * window + static_cast<std::size_t>(count) % window] = marker.best_distance;
    ++count;
    if (static_cast<std::size_t>(count) < window) continue;
    double sum = 0;
    for (std::size_t k = 0; k < window; ++k) sum += move_statistics_[node * window + k];
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
  holds_survey_prior_[static_cast<std::size_t>(moved->node)] = false;
  vacated_[static_cast<std::size_t>(moved->node)] = old_pose;
  returns_[static_cast<std::size_t>(moved->node)] = 0;
  for (const FrameMarker& marker : frame_) {
    if (marker.node >= 0) move_count_[static_cast<std::size_t>(marker.node)] = 0;
  }
  emit({SurveyEvent::Kind::moved, node_ids_[static_cast<std::size_t>(moved->node)], old_pose.head<3>(),
        new_pose.head<3>()});
}

void SurveyEstimator::update_candidates() {
  for (const FrameMarker& marker : frame_) {
    if (marker.node >= 0) continue;
    // Placed through the established marker with the most sightings seen in the same frame.
    const FrameMarker* anchor = nullptr;
    for (const FrameMarker& other : frame_) {
      if (other.node < 0 || !established(other.node)) continue;
      if (anchor == nullptr || graph_.sightings(other.node) > graph_.sightings(anchor->node)) anchor = &other;
    }
    if (anchor == nullptr) {
      ++report_.unanchored_sightings;
      continue;
    }
    const RelativeSighting relative = relative_sighting(anchor->sighting.base_in_marker, anchor->sighting.covariance,
                                                        marker.sighting.base_in_marker, marker.sighting.covariance);
    add_candidate_sighting(marker.sighting.id, compose(graph_.pose(anchor->node), relative.b_in_a));
  }
}

void SurveyEstimator::add_candidate_sighting(int id, const CeilingPose& pose) {
  Candidate* candidate = nullptr;
  Candidate* weakest = nullptr;
  for (Candidate& slot : candidates_) {
    if (slot.id == id) candidate = &slot;
    if (weakest == nullptr || slot.id < 0 || (weakest->id >= 0 && slot.sightings < weakest->sightings)) weakest = &slot;
  }
  if (candidate == nullptr) {
    // A full table gives way only to replace a one-off.
    if (weakest == nullptr || (weakest->id >= 0 && weakest->sightings > 2)) {
      ++report_.candidates_full;
      return;
    }
    *weakest = Candidate{};
    weakest->id = id;
    weakest->mean = pose;
    candidate = weakest;
  }
  if (candidate->conflict) return;
  const auto near = [&](const CeilingPose& mean) {
    const CeilingPose difference = pose_difference(pose, mean);
    return difference.head<3>().norm() < config_.candidate_radius_m &&
           std::abs(difference[3]) < config_.candidate_radius_yaw;
  };
  const auto join = [&](CeilingPose& mean, int& sightings) {
    ++sightings;
    mean += pose_difference(pose, mean) / sightings;
    mean[3] = wrap_angle(mean[3]);
  };
  if (near(candidate->mean)) {
    join(candidate->mean, candidate->sightings);
  } else if (candidate->other_sightings == 0 || near(candidate->other_mean)) {
    if (candidate->other_sightings == 0) candidate->other_mean = pose;
    join(candidate->other_mean, candidate->other_sightings);
  }
  const int half = config_.min_candidate_sightings / 2;
  if (candidate->sightings >= half && candidate->other_sightings >= half) {
    candidate->conflict = true;
    emit({SurveyEvent::Kind::conflict, id, candidate->mean.head<3>(), candidate->other_mean.head<3>()});
    return;
  }
  if (candidate->sightings < config_.min_candidate_sightings || candidate->other_sightings >= half) return;
  const int node = graph_.add_node(candidate->mean, false);
  if (node < 0) {
    ++report_.graph_full;
    return;
  }
  node_ids_[static_cast<std::size_t>(node)] = id;
  emit({SurveyEvent::Kind::added, id, Eigen::Vector3d::Zero(), candidate->mean.head<3>()});
  *candidate = Candidate{};
}

DotMarker SurveyEstimator::marker_entry(int node) const {
  const auto n = static_cast<std::size_t>(node);
  DotMarker marker;
  marker.id = node_ids_[n];
  marker.origin = graph_.pose(node).head<3>();
  marker.yaw = graph_.pose(node)[3];
  marker.pitch = node_pitch_[n];
  marker.radius = node_radius_[n];
  marker.fixed = graph_.fixed(node);
  return marker;
}

void SurveyEstimator::established_markers(std::vector<DotMarker>& markers) const {
  markers.clear();
  for (std::size_t n = 0; n < graph_.size(); ++n) {
    const int node = static_cast<int>(n);
    if (!conflicted_[n] && established(node)) {
      markers.push_back(marker_entry(node));
    }
  }
}

bool SurveyEstimator::estimate(int id, DotMarker& marker) const {
  const int node = node_of(id);
  if (node < 0 || conflicted_[static_cast<std::size_t>(node)]) return false;
  marker = marker_entry(node);
  return true;
}

MarkerMap SurveyEstimator::estimated_map() const {
  MarkerMap map = input_map_;
  map.dot_markers.clear();
  for (std::size_t n = 0; n < graph_.size(); ++n) {
    const int node = static_cast<int>(n);
    if (conflicted_[n]) continue;
    if (graph_.fixed(node)) {
      map.dot_markers.push_back(*input_map_.find_dot_marker(node_ids_[n]));  // copied unchanged
      continue;
    }
    DotMarker marker = marker_entry(node);
    marker.sigma = graph_.covariance(node).diagonal().cwiseMax(0.0).cwiseSqrt();
    map.dot_markers.push_back(marker);
  }
  return map;
}

}  // namespace irloc::survey
