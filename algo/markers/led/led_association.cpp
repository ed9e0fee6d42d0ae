#include "algo/markers/led/led_association.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "algo/geometry/p3p.hpp"
#include "algo/markers/led/level_two_point.hpp"

namespace irloc::led {
namespace {

double rotation_angle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const double cosine = 0.5 * ((a.transpose() * b).trace() - 1.0);
  return std::acos(std::clamp(cosine, -1.0, 1.0));
}

}  // namespace

LedAssociator::LedAssociator(const CameraModel& camera, const RigidTransform& base_from_camera, Dof dof,
                             const MarkerMap& map, const LedSourceConfig& config)
    : camera_(camera), base_from_camera_(base_from_camera), dof_(dof), map_(map), config_(config),
      used_(kMaxLedDetections) {
  refinement_.dof = dof;
  refinement_.loss = RobustLoss::huber;
  refinement_.loss_scale_px = config.loss_scale_px;
  refinement_.pixel_sigma = config.pixel_sigma;
}

LedAssociator::Scored LedAssociator::score(const RigidTransform& world_from_base, const LedDetectionList& detections,
                                           double gate_px, LedMatchList* matches) {
  Scored scored;
  if (matches != nullptr) matches->clear();
  std::fill(used_.begin(), used_.end(), 0);
  const RigidTransform world_from_camera = world_from_base * base_from_camera_;
  const RigidTransform camera_from_world = world_from_camera.inverse();
  const Eigen::Vector3d centre = world_from_camera.translation;
  const double gate2 = gate_px * gate_px;
  const auto& intrinsics = camera_.intrinsics();
  for (std::size_t l = 0; l < map_.led_landmarks.size(); ++l) {
    const LedLandmark& landmark = map_.led_landmarks[l];
    const Eigen::Vector3d to_camera = centre - landmark.position;
    const double range = to_camera.norm();
    if (range > config_.max_range || range < 1e-6) continue;
    // Outside its emission cone an LED sends the camera nothing.
    if (landmark.direction && landmark.half_angle &&
        landmark.direction->dot(to_camera) < std::cos(*landmark.half_angle) * range) {
      continue;
    }
    Eigen::Vector2d pixel;
    if (!camera_.project(camera_from_world * landmark.position, pixel) || !camera_.in_image(pixel)) continue;
    int nearest = -1;
    double nearest2 = gate2;
    for (std::size_t d = 0; d < detections.size(); ++d) {
      const double distance2 = (detections[d].pixel - pixel).squaredNorm();
      if (!used_[d] && distance2 < nearest2) {
        nearest2 = distance2;
        nearest = static_cast<int>(d);
      }
    }
    if (nearest >= 0) {
      used_[static_cast<std::size_t>(nearest)] = 1;
      ++scored.inliers;
      scored.cost += nearest2;
      if (matches != nullptr) matches->push_back({static_cast<int>(l), nearest});
    } else {
      const double m = config_.edge_margin_px;
      if (pixel.x() > m && pixel.y() > m && pixel.x() < intrinsics.width - 1 - m &&
          pixel.y() < intrinsics.height - 1 - m) {
        ++scored.missing;
      }
    }
  }
  return scored;
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

bool LedAssociator::few_missing(int inliers, int missing) const {
  const int allowed = static_cast<int>(config_.max_missing_fraction * (inliers + missing));
  return missing <= std::max(config_.max_missing, allowed);
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
  const Scored scored = score(world_from_base, detections, config_.search_gate_px, nullptr);
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

bool LedAssociator::refine_and_verify(const RigidTransform& start, const LedDetectionList& detections,
                                      LedMatchList& matches, LedAssociation& result) {
  RigidTransform pose = start;
  for (int pass = 0; pass < 2; ++pass) {
    if (static_cast<int>(matches.size()) < min_leds()) return false;
    fit_world_.clear();
    fit_pixels_.clear();
    for (const LedMatch& match : matches) {
      fit_world_.push_back(map_.led_landmarks[static_cast<std::size_t>(match.landmark)].position);
      fit_pixels_.push_back(detections[static_cast<std::size_t>(match.detection)].pixel);
    }
    result.fit = refine_pose(std::span<const Eigen::Vector3d>(fit_world_.begin(), fit_world_.size()),
                             std::span<const Eigen::Vector2d>(fit_pixels_.begin(), fit_pixels_.size()), camera_,
                             base_from_camera_, pose, refinement_);
    if (!result.fit.ok) return false;
    pose = result.fit.world_from_base;
    if (pass == 0) {
      const Scored scored = score(pose, detections, config_.accept_gate_px, &matches);
      result.missing = scored.missing;
    }
  }
  result.matches = matches;
  return result.fit.rms_px <= config_.max_rms_px && static_cast<int>(matches.size()) >= min_leds() &&
         few_missing(static_cast<int>(matches.size()), result.missing) && plausible(pose);
}

bool LedAssociator::search_triples(const LedDetectionList& detections,
                                   const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings, int n,
                                   int& hypotheses) {
  const auto& leds = map_.led_landmarks;
  const int m = static_cast<int>(leds.size());
  const RigidTransform camera_from_base = base_from_camera_.inverse();
  auto position = [&](int l) { return leds[static_cast<std::size_t>(l)].position; };
  auto bearing = [&](int d) { return bearings[static_cast<std::size_t>(d)]; };
  P3PSolutions solutions;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int k = j + 1; k < n; ++k) {
        if (bearing(i).squaredNorm() == 0 || bearing(j).squaredNorm() == 0 || bearing(k).squaredNorm() == 0) continue;
        const std::array<Eigen::Vector3d, 3> rays = {bearing(i), bearing(j), bearing(k)};
        for (int a = 0; a < m; ++a) {
          for (int b = 0; b < m; ++b) {
            for (int c = 0; c < m; ++c) {
              if (a == b || b == c || a == c) continue;
              if (++hypotheses > config_.max_hypotheses) return false;
              solve_p3p({position(a), position(b), position(c)}, rays, solutions);
              // T_W_B = (T_C_W)^-1 T_C_B.
              for (const RigidTransform& camera_from_world : solutions) {
                consider(camera_from_world.inverse() * camera_from_base, detections);
              }
            }
          }
        }
      }
    }
  }
  return true;
}

bool LedAssociator::search_pairs(const LedDetectionList& detections,
                                 const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings, int n,
                                 int& hypotheses) {
  const auto& leds = map_.led_landmarks;
  const int m = static_cast<int>(leds.size());
  auto position = [&](int l) { return leds[static_cast<std::size_t>(l)].position; };
  auto bearing = [&](int d) { return bearings[static_cast<std::size_t>(d)]; };
  LevelPoseSolutions solutions;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (bearing(i).squaredNorm() == 0 || bearing(j).squaredNorm() == 0) continue;
      for (int a = 0; a < m; ++a) {
        for (int b = 0; b < m; ++b) {
          if (a == b) continue;
          if (++hypotheses > config_.max_hypotheses) return false;
          solve_level_two_point({position(a), position(b)}, {bearing(i), bearing(j)}, base_from_camera_, solutions);
          for (RigidTransform pose : solutions) {
            if (dof_ == Dof::planar3 && plausible(pose)) pose.translation.z() = 0;
            consider(pose, detections);
          }
        }
      }
    }
  }
  return true;
}

void LedAssociator::search(const LedDetectionList& detections,
                           const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings, LedAssociation& result) {
  result = LedAssociation{};
  kept_.clear();
  const int n = std::min<int>(static_cast<int>(detections.size()), config_.search_detections);
  const bool complete = dof_ == Dof::full6 ? search_triples(detections, bearings, n, result.hypotheses)
                                           : search_pairs(detections, bearings, n, result.hypotheses);
  if (!complete) {
    result.outcome = "search budget exhausted";
    return;
  }
  if (kept_.empty()) {
    result.outcome = static_cast<int>(detections.size()) < min_leds() ? "too few LEDs" : "no association";
    return;
  }

  // Refine and verify the best hypotheses; keep the verified, distinct ones.
  std::sort(kept_.begin(), kept_.end(), better);
  verified_.clear();
  LedMatchList matches;
  for (const Hypothesis& hypothesis : kept_) {
    score(hypothesis.pose, detections, config_.search_gate_px, &matches);
    LedAssociation candidate;
    if (!refine_and_verify(hypothesis.pose, detections, matches, candidate)) continue;
    bool duplicate = false;
    for (const LedAssociation& other : verified_) {
      duplicate |= !distinct(other.fit.world_from_base, candidate.fit.world_from_base);
    }
    if (!duplicate) verified_.push_back(candidate);
  }
  if (verified_.empty()) {
    result.outcome = "no hypothesis verified";
    return;
  }
  auto ranked_better = [](const LedAssociation& a, const LedAssociation& b) {
    return better({a.fit.world_from_base, static_cast<int>(a.matches.size()), a.missing, a.fit.cost},
                  {b.fit.world_from_base, static_cast<int>(b.matches.size()), b.missing, b.fit.cost});
  };
  const LedAssociation* best = std::min_element(verified_.begin(), verified_.end(), ranked_better);
  // Strict acceptance: no other pose may explain as many LEDs.
  for (const LedAssociation& other : verified_) {
    if (&other != best && other.matches.size() >= best->matches.size()) {
      result.outcome = "ambiguous";
      return;
    }
  }
  const int hypotheses = result.hypotheses;
  result = *best;
  result.hypotheses = hypotheses;
  result.ok = true;
  result.outcome = "found";
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
  for (std::size_t l = 0; l < map_.led_landmarks.size(); ++l) {
    Eigen::Vector2d pixel;
    if (!camera_.project(camera_from_world * map_.led_landmarks[l].position, pixel)) continue;
    int found = -1, count = 0;
    for (std::size_t d = 0; d < detections.size(); ++d) {
      if ((detections[d].pixel - pixel).squaredNorm() < gate2) {
        found = static_cast<int>(d);
        ++count;
      }
    }
    if (count != 1) continue;
    ++used_[static_cast<std::size_t>(found)];
    matches.push_back({static_cast<int>(l), found});
  }
  LedMatchList unique;
  for (const LedMatch& match : matches) {
    if (used_[static_cast<std::size_t>(match.detection)] == 1) unique.push_back(match);
  }
  if (!refine_and_verify(predicted, detections, unique, result)) {
    result.outcome = "track lost";
    return;
  }
  const RigidTransform& pose = result.fit.world_from_base;
  if ((pose.translation - predicted.translation).norm() > config_.track_max_jump ||
      rotation_angle(pose.rotation, predicted.rotation) > config_.track_max_jump) {
    result.ok = false;
    result.outcome = "track jumped";
    return;
  }
  result.ok = true;
  result.outcome = "found";
}

}  // namespace irloc::led
