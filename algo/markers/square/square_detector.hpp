#pragma once
// The square tape marker path: a strobe pair in, the robot pose from the map's square out.
//
//   tape mask (the shared pass's foreground runs, or difference and threshold; thin lines)
//   -> ceiling plane points (per-pixel table)
//   -> Hough on the plane -> square hypotheses (search) -> for each: least-squares sides and
//   corners -> solid side and which map square by the dash pattern (and the last pose, between
//   squares of one pattern) -> c0..c3 (cross-product test) -> planar rigid fit (similarity for
//   dof 4) of every square seen at the same pose -> consistency checks -> confidence; the best
//   hypothesis, if it is clearly better than any at another pose.
//
// Everything is sized in the constructor (start-up); detect() allocates nothing and its work is
// bounded by the point capacity and the Hough peak list (overflows are counted).

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/difference_noise.hpp"
#include "algo/kernels/hough_lines.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/dash_pattern.hpp"
#include "algo/markers/square/side_refinement.hpp"
#include "algo/markers/square/square_config.hpp"
#include "algo/markers/square/square_detection.hpp"
#include "algo/markers/square/square_map_checks.hpp"
#include "algo/markers/square/square_pose.hpp"
#include "algo/markers/square/square_search.hpp"
#include "algo/markers/square/tape_levelling.hpp"
#include "algo/markers/square/tape_mask.hpp"
#include "algo/markers/square/tape_motion_fit.hpp"
#include "algo/markers/square/tape_points.hpp"

namespace irloc::square {

class SquareDetector {
 public:
  // pixel_bits: of the camera's frames (8: 8-bit frames; more: 16-bit ones). markers: the map's
  // squares; they share side, tape width and ceiling height (one ceiling table and one Hough
  // search serve them all), and their dash patterns are either the same or of periods (dash +
  // gap) at least kMinPeriodRatio apart. Throws std::invalid_argument naming the marker for a
  // marker that is not a level square above the camera, or a set that breaks the rules. Under
  // dof 6 the square is found on the level table (a tilt of a few degrees skews it a little) and
  // the pose is a 6-dof fit of its corners.
  SquareDetector(const CameraIntrinsics& camera, int pixel_bits, const RigidTransform& base_from_camera, Dof dof,
                 std::span<const SquareMarker> markers, const SquareConfig& config);
  SquareDetector(const CameraIntrinsics& camera, int pixel_bits, const RigidTransform& base_from_camera, Dof dof,
                 const SquareMarker& marker, const SquareConfig& config)
      : SquareDetector(camera, pixel_bits, base_from_camera, dof, std::span<const SquareMarker>(&marker, 1), config) {}

  // Two dash patterns are told apart by their periods; closer than this they are refused.
  static constexpr double kMinPeriodRatio = kMinDashPeriodRatio;

  // Its stages keep references to its members: it stays where it was made.
  SquareDetector(const SquareDetector&) = delete;
  SquareDetector& operator=(const SquareDetector&) = delete;

  // on, off: one strobe pair of the calibrated size and the depth set up (else outcome
  // bad_frames); noise: the pair's shared noise estimate (algo/kernels/difference_noise.hpp),
  // from which the tape threshold is derived unless the config fixes one. prior: the robot's
  // recent pose, if any (tells apart squares of one pattern). rows: under a rolling shutter, the
  // motion within the frame; the tape points are then moved to the frame's t_ns before the sides
  // are fitted (TapePoints::collect), and the pose and corner pixels are those at t_ns.
  SquareDetection detect(const GrayImageView& on, const GrayImageView& off, const DifferenceNoise& noise,
                         const RigidTransform* prior = nullptr, const RowMotion* rows = nullptr);
  // The same after the pair's shared pass (pair_pass.hpp) over on and off: its noise estimate,
  // and its foreground runs as the tape mask's binary mask when they are at the tape threshold
  // and complete (detection.mask_from_shared_pass); else the mask's own pass over the pair.
  SquareDetection detect(const GrayImageView& on, const GrayImageView& off, const PairPass& pair,
                         const RigidTransform* prior = nullptr, const RowMotion* rows = nullptr);
  // The stages after the tape mask (of the frame region whose top-left pixel is (x0, y0)), for
  // tests and benchmarks.
  SquareDetection detect_in_mask(const BitImage& mask, int x0, int y0, const RigidTransform* prior = nullptr,
                                 const RowMotion* rows = nullptr);
  // Under a rolling shutter with no motion known: the pose at t_ns and the motion within the frame
  // fitted to the tape points of `detection`, which the last detect() found without a motion
  // (TapeMotionFitter, line_time: seconds a row; prior: on the motion, nullopt for none). Not ok
  // when not found, and under dof 6 (a tilt skews the square as a drive does).
  TapeMotionFit fit_motion(const SquareDetection& detection, double line_time,
                           const std::optional<MotionPrior>& prior);
  const CeilingPlaneMap& plane() const { return plane_; }

  std::span<const SquareMarker> markers() const { return markers_; }
  double side() const { return side_; }
  int element_radius() const { return element_radius_; }

 private:
  // Squares of one dash pattern (indices into markers_).
  struct PatternGroup {
    DashGeometry geometry;
    std::vector<std::size_t> members;
  };
  // One square hypothesis: its refined sides and, once it passed every check, which map square it
  // is (corners c0..c3 on the table) and what it reports (pose, dash patterns, solid side).
  struct SquareHypothesis {
    SquareFit fit;
    IdentifiedSquare square;
    SquareDetection detection;
  };
  static constexpr int kMaxRidgeRefits = 8;
  static constexpr std::size_t kMaxRidgeSides = 3;
  // The hypotheses of one pair (of both searches under dof 6), in the order scored; in place,
  // cleared per pair.
  struct FrameHypotheses {
    StaticVector<SquareHypothesis, 2 * kMaxSquareCandidates + kMaxRidgeRefits> passed;
    // Refined but did not pass: tried again on other ridges (refit_on_other_ridges) when none passed.
    StaticVector<SquareFit, 2 * kMaxSquareCandidates> failed;
    SquareOutcome outcome = SquareOutcome::no_square;  // why the strongest did not pass
    std::uint32_t merged = 0;                          // variants of a passed one, not scored
    int ridge_refits_left = kMaxRidgeRefits;

    void clear() {
      passed.clear();
      failed.clear();
      outcome = SquareOutcome::no_square;
      merged = 0;
      ridge_refits_left = kMaxRidgeRefits;
    }
  };
  // The squares one hypothesis may be (pose_options()), one per map square at most.
  struct Option {
    IdentifiedSquare square;
    SquareDetection detection;
  };
  using SidePoints = std::array<std::span<const Eigen::Vector2d>, 4>;

  // detect() with the shared pass's runs, if any.
  SquareDetection detect_pair(const GrayImageView& on, const GrayImageView& off, const DifferenceNoise& noise,
                              const PairPass* pair, const RigidTransform* prior, const RowMotion* rows);
  // The stages over the frame's tape points and Hough peaks: the hypotheses of the level search
  // (and under dof 6 the tilted one) scored into frame_, and when none passed the failed ones
  // refitted on other ridges.
  void find_hypotheses(const RigidTransform* prior);
  // Scores candidates_ into frame_ (evaluate()) after the hypotheses already there. With none
  // passed before, frame_.outcome says why the strongest did not pass (no_square: no candidate).
  void score_candidates(const RigidTransform* prior);
  // A refined hypothesis that did not pass, refitted with the other ridge of points beside its
  // sides (SquareRefiner::side_ridges): each choice of ridges for up to kMaxRidgeSides sides,
  // while frame_.ridge_refits_left lasts. Each that passes is added to frame_.passed.
  void refit_on_other_ridges(const SquareFit& fit, const RigidTransform* prior);
  // A refined hypothesis that passes every check is added to frame_.passed (its sides
  // straightened when loose: straighten_if_loose()); else the outcome says why not.
  SquareOutcome add_if_passed(const SquareFit& fit, const RigidTransform* prior);
  // One hypothesis, its sides refined: the dash pattern, which square, the pose (into
  // hypothesis.square and .detection); the outcome says why not.
  SquareOutcome evaluate(SquareHypothesis& hypothesis, const RigidTransform* prior);
  // dof 6: evaluate() on the tape levelled at the hypothesis' own tilt.
  SquareOutcome evaluate_tilted(SquareHypothesis& hypothesis, const RigidTransform* prior);
  // A hypothesis that passed with a loose fit (corner RMS above kCloseFitCornerRms of the check's
  // limit), posed again on its straightened sides (SquareRefiner::straighten) when a side moves and
  // the pose's corners then fit the map's square at least twice as closely; else unchanged.
  void straighten_if_loose(SquareHypothesis& hypothesis);
  // The dash patterns of the refined square (measured: its corners where the points were mapped;
  // points[k]: those that may lie on side k), which map square it is, its pose.
  SquareOutcome classify(const std::array<Eigen::Vector2d, 4>& measured, const SidePoints& points,
                         const RigidTransform* prior, SquareHypothesis& hypothesis);
  // The squares the hypothesis may be, posed, into options_; their count. With none, why_not says
  // why; several_groups: squares of two dash patterns matched.
  std::size_t pose_options(const SquareFit& fit, const std::array<Eigen::Vector2d, 4>& measured,
                           const SidePoints& points, SquareOutcome& why_not, bool& several_groups);
  // The best passed hypothesis, fused with the other squares at its pose; ambiguous when one at
  // another pose is nearly as good.
  SquareDetection choose() const;
  // dof 6: the tilt of a refined quadrilateral (the 6-dof fit to the first map square).
  bool probe_tilt(const std::array<Eigen::Vector2d, 4>& corners, RollPitchYaw& tilt) const;

  SquareConfig config_;
  Dof dof_;
  std::vector<SquareMarker> markers_;
  std::vector<double> map_turns_;  // turn(c0, c1, c2) of each marker
  std::vector<PatternGroup> groups_;
  RigidTransform base_from_camera_;
  double side_ = 0;       // d from the map, metres
  double ceiling_z_ = 0;  // of the markers in W
  int element_radius_ = 0;
  std::uint32_t min_side_points_ = 0;
  CameraModel camera_;
  CeilingPlaneMap plane_;
  SquarePoser poser_;
  TapeMask tape_mask_;
  TapePoints tape_points_;
  TapeMotionFitter motion_fitter_;
  SquareRefiner refiner_;
  HoughLines hough_;
  HoughLineList peaks_;
  SquareCandidates candidates_;
  LevelledTape levelled_;  // dof 6: the frame's tape at the tilt of the hypothesis being read
  FrameHypotheses frame_;
  std::vector<Option> options_;
};

}  // namespace irloc::square
