// LedAssociator's search (led_association.hpp): minimal sets of detections (three bearings by
// P3P, or two under a level robot) against the map's LEDs, each hypothesis refined and verified,
// the winner taken only by a margin over its rivals.
#include <algorithm>
#include <cmath>

#include "algo/geometry/p3p.hpp"
#include "algo/markers/led/led_association.hpp"
#include "algo/markers/led/level_two_point.hpp"

namespace irloc::led {

int LedAssociator::detections_to_cover(int n, int minimal_set) const {
  // A pose that matches K of the n detections matches at least `minimal_set` of any
  // n - K + minimal_set of them: the minimal sets drawn from that many detections find every pose
  // that could be the winner or compete with it (K down to the best's explained LEDs less the
  // margin, one LED of slack for what refinement changes).
  int best = 0;
  for (const Hypothesis& hypothesis : kept_) best = std::max(best, hypothesis.inliers - hypothesis.missing);
  const int fewest = std::max(min_leds(), best - config_.min_margin_leds);
  return kept_.empty() ? n : std::min(n, n - fewest + minimal_set);
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
  // Triples by their last detection: after k, every triple of the first k + 1 detections is done.
  for (int k = 2; k < n && k < detections_to_cover(n, 3); ++k) {
    for (int j = 1; j < k; ++j) {
      for (int i = 0; i < j; ++i) {
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
  // Where noise merges the two-point form's roots, its nearest pose counts if it puts the pair's
  // second LED within the search gate (in radians at the image centre).
  const double vertex_angle = config_.search_gate_px / camera_.intrinsics().fx;
  // Pairs by their last detection: after j, every pair of the first j + 1 detections is done.
  for (int j = 1; j < n && j < detections_to_cover(n, 2); ++j) {
    for (int i = 0; i < j; ++i) {
      if (bearing(i).squaredNorm() == 0 || bearing(j).squaredNorm() == 0) continue;
      for (int a = 0; a < m; ++a) {
        for (int b = 0; b < m; ++b) {
          if (a == b) continue;
          if (++hypotheses > config_.max_hypotheses) return false;
          solve_level_two_point({position(a), position(b)}, {bearing(i), bearing(j)}, base_from_camera_, solutions,
                                vertex_angle);
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
  winner_ = -1;
  const int n = std::min<int>(static_cast<int>(detections.size()), config_.search_detections);
  const bool complete = dof_ == Dof::full6 ? search_triples(detections, bearings, n, result.hypotheses)
                                           : search_pairs(detections, bearings, n, result.hypotheses);
  if (!complete) {
    result.outcome = LedOutcome::search_budget_exhausted;
    return;
  }
  if (kept_.empty()) {
    result.outcome = static_cast<int>(detections.size()) < min_leds() ? LedOutcome::too_few_leds : LedOutcome::no_association;
    return;
  }

  // Refine and verify the best hypotheses; keep the verified, distinct ones.
  std::sort(kept_.begin(), kept_.end(), better);
  verified_.clear();
  LedMatchList matches;
  for (const Hypothesis& hypothesis : kept_) {
    score(hypothesis.pose, detections, config_.search_gate_px, &matches, nullptr, known_motion());
    verify_distinct(hypothesis.pose, detections, matches);
  }
  if (verified_.empty()) {
    result.outcome = LedOutcome::no_hypothesis_verified;
    return;
  }
  auto ranked_better = [](const LedAssociation& a, const LedAssociation& b) {
    return better({a.fit.world_from_base, static_cast<int>(a.matches.size()), a.missing, a.fit.cost},
                  {b.fit.world_from_base, static_cast<int>(b.matches.size()), b.missing, b.fit.cost});
  };
  const LedAssociation* best = std::min_element(verified_.begin(), verified_.end(), ranked_better);
  bool as_many_matched = false;
  const int margin = margin_over_rivals(*best, as_many_matched);
  if (margin < config_.min_margin_leds || as_many_matched) {
    result.outcome = LedOutcome::ambiguous;
    result.margin = margin;
    return;
  }
  if (static_cast<int>(best->matches.size()) < min_confirmed_leds()) {
    result.outcome = LedOutcome::unconfirmed;
    result.margin = margin;
    winner_ = static_cast<int>(best - verified_.begin());
    return;
  }
  accept(*best, margin, detections, result);
}

int LedAssociator::margin_over_rivals(const LedAssociation& best, bool& as_many_matched) const {
  // Strict acceptance: the winner explains min_margin_leds more LEDs (matched less missing) than
  // any other confirmed pose that passed verification, and matches more LEDs than each: a missing
  // LED may be dead or hidden, so fewer missing alone does not decide between two poses that fit
  // as many (a flat cluster's mirrored pose that puts a dead LED outside its cone). A pose that
  // matches no LED beyond its minimal set is no competitor: it fits that set exactly, so one
  // exists for nearly any detections; it is evidence of nothing (nor accepted itself: confirmation).
  auto explained = [](const LedAssociation& a) { return static_cast<int>(a.matches.size()) - a.missing; };
  int runner_up = 0;
  as_many_matched = false;
  for (const LedAssociation& other : verified_) {
    if (&other != &best && static_cast<int>(other.matches.size()) >= min_confirmed_leds()) {
      runner_up = std::max(runner_up, explained(other));
      as_many_matched |= other.matches.size() >= best.matches.size();
    }
  }
  return explained(best) - runner_up;
}

void LedAssociator::accept(const LedAssociation& winner, int margin, const LedDetectionList& detections,
                           LedAssociation& result) {
  const int hypotheses = result.hypotheses;
  result = winner;
  result.hypotheses = hypotheses;
  result.margin = margin;
  result.ok = true;
  result.outcome = LedOutcome::found;
  collect_missed(result, detections, missed_, last_unseen_);
}

}  // namespace irloc::led
