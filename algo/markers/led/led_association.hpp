#pragma once
// Which mapped LED is which detection, and the pose that says so. The LEDs carry no ID, so a pose
// is only reported when one association explains the image clearly better than every other:
//
// - search(): hypotheses from minimal sets (P3P on triples of detections and ordered triples of
//   mapped LEDs under dof 6; the level two-point closed form on pairs under dof 3 and 4), pruned by
//   the dof (tilt, height), then scored by how many mapped LEDs, projected where they emit toward
//   the camera and fall in the image, land on a detection. The best few are refined (non-linear
//   least squares, pose_refinement.hpp) and verified; if two different poses are left with the
//   same number of matched LEDs, the scene is ambiguous and there is no pose.
// - track(): from a predicted pose, each mapped LED is matched to the one detection near its
//   prediction; refined and verified the same way, and it must stay near the prediction. It may
//   miss only LEDs that the last pose (searched or tracked) did not see: a dead or hidden LED stays
//   so, while a track shifted by one LED along a row newly misses the row's end.
//
// Every hypothesis starts from an exact solution of a minimal set, so the refinement starts in
// the basin of the true minimum (the paper's experiment 3 started from a fixed guess instead).
// Buffers are sized at construction; search() and track() allocate nothing. Each pose considered
// costs the LEDs near the camera (led_neighbourhood.hpp: at most led.max_leds_in_range), never the
// map's size; a search tries at most led.max_hypotheses.

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/led/led_config.hpp"
#include "algo/markers/led/led_detector.hpp"
#include "algo/markers/led/led_neighbourhood.hpp"
#include "algo/markers/led/led_outcome.hpp"
#include "algo/source/source_input.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::led {

struct LedMatch {
  int landmark = -1;   // index in map.led_landmarks
  int detection = -1;  // index in the detection list
};
using LedMatchList = StaticVector<LedMatch, kMaxLedDetections>;

struct LedAssociation {
  bool ok = false;
  LedOutcome outcome = LedOutcome::no_association;
  PoseFit fit;
  LedMatchList matches;
  int missing = 0;           // mapped LEDs predicted well inside the image without a detection
  int hypotheses = 0;        // minimal-set solutions tried (search) or 1 (track)
  // Search: LEDs the winner explains (matched less missing) beyond the best other verified pose.
  int margin = 0;
  // Under a rolling shutter: the motion within the frame the fit moved the mapped LEDs with, so
  // that fit.world_from_base is the pose at the frame's t_ns (set_rolling_shutter); empty: a plain
  // fit to the row-skewed centres (a global shutter, or too few LEDs to fit the motion).
  std::optional<FrameMotion> motion;
  bool motion_fitted = false;  // the motion was fitted with the pose to this frame's LEDs
  // With the motion fitted under a prior (set_rolling_shutter): what its uncertainty adds to
  // fit.covariance (PoseMotionFit::motion_pose_covariance); zero otherwise.
  PoseCovariance motion_covariance = PoseCovariance::Zero();
};

class LedAssociator {
 public:
  // Keeps references to camera, mount and map: they outlive it (the Localizer's set-up).
  LedAssociator(const CameraModel& camera, const RigidTransform& base_from_camera, Dof dof,
                const MarkerMap& map, const LedSourceConfig& config);

  // Bearings (unit, camera frame) of the detections, same order; invalid ones are zero.
  void search(const LedDetectionList& detections, const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings,
              LedAssociation& result);
  void track(const RigidTransform& predicted_world_from_base, const LedDetectionList& detections,
             LedAssociation& result);
  // After a search that ended `unconfirmed` (its winner matches only a minimal set): accepts the
  // winner when it lies within track_max_jump (metres and radians) of the track's prediction and is
  // the only verified pose there. The prediction is the evidence tracking accepts a minimal set on;
  // the search's other poses stand in for tracking's pixel gate (a shifted association near the
  // prediction is a second pose there: no pose). true when it accepted; else `result` is unchanged.
  bool confirm_by_track(const RigidTransform& predicted_world_from_base, const LedDetectionList& detections,
                        LedAssociation& result);
  // Forgets the LEDs the last pose missed (a track's start).
  void restart() { last_unseen_.clear(); }
  // The next attempts' glare (led_detector.hpp): an LED predicted within edge_margin_px of a box
  // is hidden there, not missing (as at the image's border).
  void set_glare(const LedGlareList& glare) { glare_ = glare; }
  // The next attempts' rolling shutter (rolling_shutter.hpp): row v seen v x line_time_s after
  // t_ns (0: a global shutter), and the robot's motion within the frame when known. Known, every
  // fit moves each mapped LED to where the robot at t_ns sees it; unknown, the motion is fitted
  // with the pose where the matched LEDs leave the residual a test of the association
  // (kMinFreedomWithMotion), else the fit is plain; motion_prior: that fit's prior on the motion
  // (the motion before a gap, SourceInput::motion_prior), nullopt for none. Either way the
  // residual is judged after the motion within the frame: row-skewed centres fail the
  // centre-noise test otherwise.
  void set_rolling_shutter(double line_time_s, const std::optional<FrameMotion>& motion,
                           const std::optional<MotionPrior>& motion_prior) {
    line_time_ = line_time_s;
    motion_ = motion;
    motion_prior_ = motion_prior;
  }

  // Fewest matched LEDs that determine a pose under the dof.
  int min_leds() const { return dof_ == Dof::full6 ? 3 : 2; }
  // Fewest matched LEDs a searched pose needs: one beyond the minimal set it was solved from. The
  // solver fits any detections of a minimal set exactly (under dof 3 but for the base height), so
  // only an LED beyond the set tests the association: with a spurious point among the detections,
  // some of the many minimal-set solutions explains it and one LED by chance.
  int min_confirmed_leds() const { return min_leds() + 1; }

 private:
  struct Hypothesis {
    RigidTransform pose;
    int inliers = 0;
    int missing = 0;
    double cost = 0;
  };
  struct Scored {
    int inliers = 0;
    int missing = 0;
    double cost = 0;
  };

  // Matches every mapped LED near the camera that it would see from `pose` to its nearest unused
  // detection within gate_px; the LEDs counted missing go to `missed` when it is given.
  // Under a rolling shutter with `motion`, each LED is predicted where the robot at t_ns sees it.
  // Where mapped LED l shows from this pose (at its row's time under `motion`), if the camera is
  // within its range and its cone; must_be_seen: well inside the cone.
  struct PredictedLed {
    Eigen::Vector2d pixel;
    double range = 0;
    bool must_be_seen = true;
  };
  std::optional<PredictedLed> predict(int l, const RigidTransform& world_from_base, const RigidTransform& world_from_camera,
                                      const RigidTransform& camera_from_world, const FrameMotion* motion) const;
  // The detection not yet used nearest to pixel, closer than sqrt(distance2) (then set to its
  // squared distance); -1: none.
  int nearest_unused(const Eigen::Vector2d& pixel, const LedDetectionList& detections, double& distance2) const;
  Scored score(const RigidTransform& world_from_base, const LedDetectionList& detections, double gate_px,
               LedMatchList* matches, std::vector<int>* missed = nullptr, const FrameMotion* motion = nullptr);
  // Whether a tracked pose misses an LED that the last pose saw (fills missed_ and unseen_now_).
  bool misses_a_seen_led(const LedAssociation& association, const LedDetectionList& detections);
  // The LEDs that the association's pose misses (accept_gate_px) into `missed`, and every LED it
  // predicts without seeing (missed or too faint to be) into `unseen`; both sorted.
  void collect_missed(const LedAssociation& association, const LedDetectionList& detections, std::vector<int>& missed,
                      std::vector<int>& unseen);
  // The motion within the frame under a rolling shutter, when known; else nullptr.
  const FrameMotion* known_motion() const { return line_time_ > 0 && motion_ ? &*motion_ : nullptr; }
  bool plausible(const RigidTransform& world_from_base) const;
  // The pixel lies within edge_margin_px of a glare box.
  bool in_glare(const Eigen::Vector2d& pixel) const;
  bool few_missing(int inliers, int missing) const;
  // The fit's residual is what centre noise of pixel_sigma leaves (motion_parameters: fitted
  // besides the pose).
  bool residual_consistent(const PoseFit& fit, int matched, int motion_parameters) const;
  // The mapped LEDs of `matches` and their detections into fit_world_ and fit_pixels_, each LED
  // moved to where the robot at t_ns (world_from_base) sees it under `motion` (when given).
  void collect_fit_points(const LedMatchList& matches, const LedDetectionList& detections,
                          const RigidTransform& world_from_base, const FrameMotion* motion);
  bool distinct(const RigidTransform& a, const RigidTransform& b) const;
  static bool better(const Hypothesis& a, const Hypothesis& b);
  void consider(const RigidTransform& world_from_base, const LedDetectionList& detections);
  // How many of the n first detections the minimal sets (of minimal_set detections) must be
  // drawn from to find every pose that the hypotheses kept so far could lose to or tie with.
  int detections_to_cover(int n, int minimal_set) const;
  // The hypotheses of the n first detections: P3P on triples (dof 6) or the level two-point form
  // on pairs (dof 3, 4), each against every ordered set of mapped LEDs, the detections taken in
  // order until detections_to_cover() are done. false when max_hypotheses ran out before the end.
  bool search_triples(const LedDetectionList& detections, const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings,
                      int n, int& hypotheses);
  bool search_pairs(const LedDetectionList& detections, const StaticVector<Eigen::Vector3d, kMaxLedDetections>& bearings,
                    int n, int& hypotheses);
  // A detection that no match uses lies among the matched ones (their box grown by the tracking
  // gate).
  bool leaves_detection_unexplained(const LedDetectionList& detections, const LedMatchList& matches);
  // Refines from a starting pose and its matches, re-matches within accept_gate_px, refines
  // again; false when the result fails a check.
  bool refine_and_verify(const RigidTransform& start, const LedDetectionList& detections, LedMatchList& matches,
                         LedAssociation& result);
  // The LEDs the search's winner explains beyond every other confirmed verified pose (strict
  // acceptance); as_many_matched: one of those matches as many LEDs as the winner.
  int margin_over_rivals(const LedAssociation& best, bool& as_many_matched) const;
  // The winner into `result` as `found` (keeping its hypotheses count), and the LEDs it misses
  // and predicts unseen remembered for the track.
  void accept(const LedAssociation& winner, int margin, const LedDetectionList& detections, LedAssociation& result);
  // refine_and_verify from `start`; the result joins verified_ unless it is the same pose as one
  // there.
  void verify_distinct(const RigidTransform& start, const LedDetectionList& detections, LedMatchList& matches);

  const CameraModel& camera_;
  const RigidTransform& base_from_camera_;
  Dof dof_;
  const MarkerMap& map_;
  LedSourceConfig config_;
  RefinementOptions refinement_;
  double line_time_ = 0;                 // s a row; 0: a global shutter
  std::optional<FrameMotion> motion_;    // within the frame, when known
  std::optional<MotionPrior> motion_prior_;  // on the motion fitted with the pose, when given
  static constexpr std::size_t kKeptHypotheses = 12;
  StaticVector<Hypothesis, kKeptHypotheses> kept_;
  StaticVector<LedAssociation, kKeptHypotheses> verified_;
  int winner_ = -1;  // the last search's winner in verified_ when it ended `unconfirmed`, else -1
  LedNeighbourhood neighbourhood_;
  std::vector<int> near_;   // the LEDs near the camera, during score() and track()
  // The LEDs the last ok pose predicted without seeing them, and the current pose's (sorted); the
  // LEDs the current pose misses.
  std::vector<int> last_unseen_, unseen_now_, missed_;
  struct UnseenLed {
    int landmark = -1;
    double range = 0;     // m, from the camera
    bool hidden = false;  // in glare: never missing
  };
  // Predicted well inside the image and the cone, not matched, during score().
  std::vector<UnseenLed> unseen_;
  LedGlareList glare_;
  std::vector<char> used_;  // per detection, during score()
  StaticVector<Eigen::Vector3d, kMaxLedDetections> fit_world_;
  StaticVector<Eigen::Vector2d, kMaxLedDetections> fit_pixels_;
  StaticVector<double, kMaxLedDetections> fit_row_times_;
};

}  // namespace irloc::led
