#pragma once
// The oracle of ambiguity by nature for bench_led_goal (issue 26): whether the bright points a
// frame shows leave another pose as good as the truth, whatever a source does. Independent of the
// LED source's search and verification: it uses only the map, the camera model and the two
// minimal-set solvers (P3P under dof 6, the level two-point closed form under dof 3 and 4), on the
// spots' true image positions, noise-free.
//
// The bright points: the LEDs the renderer vouches for (LedFamilyPair::visible) and the spurious
// always-on points it vouches for (LedFamilyPair::stray). By position a spurious point is an LED
// to any source; retro-reflectors are not counted, the strobe pair tells them apart (dark in the
// LED-off frame). A pose explains a bright point when a mapped LED that may emit toward the camera
// (inside the map's cone widened by kAxisTolerance, the most the family's axes are off the map's)
// projects within kExplainsPx of it. A pose predicts an unseen LED when a mapped LED surely emits
// toward it (inside the map's cone narrowed by kAxisTolerance) and projects well inside the image
// (edge_margin_px) with no bright point within kExplainsPx: a dead LED, one too dim, or one hidden
// by clutter, which an image cannot tell apart.
//
// Ambiguous by nature: another pose the robot may have (level under dof 3 and 4, its height and
// tilt within the source's limits; distinct from the truth by more than kDistinctPosition or
// kDistinctAngle) explains at least as many bright points as the truth does and predicts no more
// unseen LEDs than the truth does.
//
// Candidates: the minimal-set solutions (k = 3 points under dof 6, 2 under dof 3 and 4) of every
// k-subset of the first N - E + k bright points (N bright points, E of them explained by the
// truth) against every ordered k-tuple of mapped LEDs. Complete: a rival explains at least E of
// the N points, so it leaves at most N - E unexplained, and among any N - E + k points explains at
// least k; solved from those, it is a candidate. Bounded: with every bright point an LED (E = N)
// that is the first k points, as before; each spurious point adds one point to draw from. The
// exact fit of k points may leave the others off by more than kExplainsPx where a least-squares
// pose explains them all (the flip of a far, flat cluster under dof 6: 2.4 px off one LED, 0.9 m
// low, where the refined flip fits every LED within 0.2 px at a plausible height); so a candidate
// that lies within kNearPx of as many points as the truth explains is refined over them
// (refine_pose at the config's loss and centre noise) and judged again.
//
// A stray light's rival (stray_light_rival): the truth explains exactly a minimal set of the
// bright points (k), and another pose the robot may have (plausible, in the room: in front of every
// mapped LED's mounting surface) explains k - 1 of them by LEDs that surely emit toward it (the
// map's cone narrowed by kAxisTolerance), leaves the rest to a stray light, and shows no other LED
// that may emit toward it (the cone widened) anywhere in the image: an image that the robot there,
// with a stray light, gets whatever the true axes and however dim the LEDs. An exact fit of k points
// exists for nearly any k points, so k points explained are no evidence that they are LEDs; a
// stray always-on light is in view in a share of the family's scenes (and of rooms), and the robot
// at the rival, seeing one LED fewer and the light, gets the same image. With k + 1 points or more
// explained, a rival of one fewer needs the stray light to fall where the truth puts an LED: a
// coincidence, not a second explanation. Searched over the continuum of such poses: under dof 3
// and 4 (k - 1 = 1) every bright point as every mapped LED, the level poses that put it there
// (yaw in kRivalYawStep steps; under dof 4 the range in kRivalRanges geometric steps and at every
// kRivalHeightStep of the height limits); under dof 6 (k - 1 = 2) every pair of bright points as
// every ordered pair of mapped LEDs, the base tilted by every roll and pitch of a grid of
// kRivalTiltSteps per side within max_tilt, the level two-point solutions of each tilt. A rival
// region narrower than the grid's step may be missed: the frame then counts as decided.

#include <array>
#include <functional>
#include <numbers>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/markers/led/led_landmark_source.hpp"
#include "host_sim/render/led_family_frames.hpp"
#include "host_sim/scenario/led_scene_family.hpp"

namespace irloc::test {

class AmbiguityOracle {
 public:
  static constexpr double kExplainsPx = 1.5;
  static constexpr double kNearPx = 6;  // a candidate this close to as many points as the truth explains is refined
  static constexpr double kDistinctPosition = 0.05, kDistinctAngle = 0.02;  // metres, radians
  static constexpr double kAxisTolerance = 15 * std::numbers::pi / 180;  // radians
  static constexpr double kRivalYawStep = 2 * std::numbers::pi / 180;      // radians
  static constexpr int kRivalRanges = 32;                                   // from kRivalMinRange to max_range
  static constexpr double kRivalMinRange = 0.3, kRivalHeightStep = 0.05;    // metres
  static constexpr int kRivalTiltSteps = 5;                                 // each side of level, to max_tilt

  AmbiguityOracle(const sim::LedFamilyScene& scene, const led::LedSourceConfig& config);

  // Whether the frame whose truth is `truth` and whose bright points are pair.visible and
  // pair.stray is ambiguous by nature (above). With fewer bright points than a minimal set: false.
  bool ambiguous(const RigidTransform& truth, const sim::LedFamilyPair& pair) const;

  // Which LED axes a stray light's rival must hold for: every axis within kAxisTolerance of the
  // map's (the rival gets the same image whatever the true axes: above), or some (its LEDs may emit
  // toward it and every other may not: the map, which states the axes to within kAxisTolerance,
  // cannot refute it, though the scene's true axes may), or the installed ones (the scene's true
  // axes and cones, a dead LED dark: the robot there, in this room, gets the same image).
  enum class RivalAxes { every, some, installed };
  // A stray light's rival of the frame (above), if the truth explains exactly a minimal set of the
  // bright points and one exists; `shows`, if given, must hold for it too (the renderer's verdict:
  // the robot there sees the rival's LEDs, bright enough).
  std::optional<RigidTransform> stray_light_rival(const RigidTransform& truth, const sim::LedFamilyPair& pair,
                                                  RivalAxes axes = RivalAxes::every,
                                                  const std::function<bool(const RigidTransform&)>& shows = {}) const;

 private:
  // The level poses (under dof 3 at height 0, under dof 4 within the height limits) that put the
  // mapped LED `led` on the bearing `bearing` (camera frame); the first for which `is_rival` holds.
  template <typename IsRival>
  std::optional<RigidTransform> one_point_rival(const Eigen::Vector3d& led, const Eigen::Vector3d& bearing,
                                                const IsRival& is_rival) const;
  // The tilted poses that put the mapped LEDs `leds` on the bearings `bearings`; the first rival.
  template <typename IsRival>
  std::optional<RigidTransform> two_point_rival(const std::array<Eigen::Vector3d, 2>& leds,
                                                const std::array<Eigen::Vector3d, 2>& bearings,
                                                const IsRival& is_rival) const;
  bool plausible(const RigidTransform& pose) const;
  std::span<const LedLandmark> mapped() const { return scene_.map.led_landmarks; }
  // The points one of `leds` inside its cone widened by `widen` (radians; negative: narrowed)
  // projects within kExplainsPx of.
  int explained(std::span<const LedLandmark> leds, const RigidTransform& pose, std::span<const Eigen::Vector2d> points,
                double widen = kAxisTolerance) const;
  // Those of `leds` inside their cones widened by `widen` that project more than `margin` px inside
  // the image with no point within kExplainsPx.
  int unseen(std::span<const LedLandmark> leds, const RigidTransform& pose, std::span<const Eigen::Vector2d> points,
             double widen = -kAxisTolerance, double margin = -1) const;  // margin < 0: edge_margin_px
  // A stray light's rival (stray_light_rival): plausible, in the room, distinct from the truth,
  // explaining k - 1 points and not all of the truth's k, and showing no other LED, for every
  // (or some) true axes within kAxisTolerance of the map's, or for the installed ones.
  bool robust_stray_light_rival(const RigidTransform& pose, const RigidTransform& truth,
                                std::span<const Eigen::Vector2d> points, std::span<const Eigen::Vector2d> truth_points,
                                RivalAxes axes) const;
  bool may_emit_toward(const LedLandmark& mapped, const Eigen::Vector3d& camera, double widen) const;
  // The least-squares pose (refine_pose, from `pose`) of the bright points that a mapped LED
  // projects within kNearPx of, when they are at least truth_explained; false otherwise.
  bool refined(const RigidTransform& pose, std::span<const Eigen::Vector2d> points, int truth_explained,
               RigidTransform& refined_pose) const;
  bool rival(const RigidTransform& pose, const RigidTransform& truth, std::span<const Eigen::Vector2d> points,
             int truth_explained, int truth_unseen) const;
  // Every minimal-set solution of the points `subset` (indices into points) against every ordered
  // tuple of mapped LEDs; true once one is a rival.
  bool any_rival_from(std::span<const int> subset, const RigidTransform& truth, std::span<const Eigen::Vector2d> points,
                      int truth_explained, int truth_unseen) const;

  const sim::LedFamilyScene& scene_;
  std::vector<LedLandmark> installed_lit_;  // scene_.leds (the true axes) less the dead ones
  CameraModel camera_;
  led::LedSourceConfig config_;
};

// The renderer's verdict on a stray light's rival of the frame `pair` (attempt `attempt` of
// `scene`): with the robot standing at `rival`, it vouches (LedFamilyPair::visible) for a minimal
// set less one of LEDs, each on one of the frame's bright points, and for no other LED; so the
// robot there, with a stray light where the truth sees the last LED, gets the frame's bright points
// (the rival's LEDs bright enough, which the oracle's geometry does not judge). at_rival: scratch.
bool renderer_shows_stray_light_rival(const sim::LedFamilyScene& scene, int attempt, const RigidTransform& rival,
                                      const sim::LedFamilyPair& pair, double threshold, sim::LedFamilyPair& at_rival);

}  // namespace irloc::test
