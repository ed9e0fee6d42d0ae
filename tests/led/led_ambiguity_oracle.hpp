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

#include <numbers>
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

  AmbiguityOracle(const sim::LedFamilyScene& scene, const led::LedSourceConfig& config);

  // Whether the frame whose truth is `truth` and whose bright points are pair.visible and
  // pair.stray is ambiguous by nature (above). With fewer bright points than a minimal set: false.
  bool ambiguous(const RigidTransform& truth, const sim::LedFamilyPair& pair) const;

 private:
  bool plausible(const RigidTransform& pose) const;
  int explained(const RigidTransform& pose, std::span<const Eigen::Vector2d> points) const;
  int unseen(const RigidTransform& pose, std::span<const Eigen::Vector2d> points) const;
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
  CameraModel camera_;
  led::LedSourceConfig config_;
};

}  // namespace irloc::test
