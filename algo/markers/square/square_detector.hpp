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
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

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
#include "algo/markers/square/square_search.hpp"
#include "algo/markers/square/tape_mask.hpp"
#include "algo/markers/square/tape_motion_fit.hpp"
#include "algo/markers/square/tape_points.hpp"

namespace irloc {

// Why a frame gave no pose (for logs and tests); found when it did.
enum class SquareOutcome {
  found,
  bad_frames,       // the pair's frames differ in depth or are not of the calibrated size
  no_square,        // no four Hough peaks form a square of side d
  sides_too_thin,   // a side has too few tape points to refine
  side_hidden,      // a side is seen along less than min_visible_fraction of it
  solid_ambiguous,  // not exactly one side reads solid
  inconsistent,     // the refined square does not match the map (corner residual, side length)
  ambiguous,        // two hypotheses at different poses explain the tape about equally well
  unidentified,     // a square whose pattern no map square has, or one of several alike
                    // without a recent pose near one of them
};

// Squares fused into one pose when they are seen together.
inline constexpr std::size_t kMaxSquaresInView = 2;
using SquareCornerPixels = std::array<std::array<Eigen::Vector2d, 4>, kMaxSquaresInView>;
inline SquareCornerPixels no_corner_pixels() {
  SquareCornerPixels pixels;
  for (auto& square : pixels) square.fill(Eigen::Vector2d::Zero());
  return pixels;
}
std::string_view to_string(SquareOutcome outcome);

struct SquareDetection {
  SquareOutcome outcome = SquareOutcome::no_square;
  RigidTransform world_from_base;  // T_W_B when found
  double confidence = 0;           // in [0, 1]
  // Of (x, y, z, roll, pitch, yaw) of T_W_B, from the fit of the four corners (level_fit_covariance).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  // The map squares the pose is from (indices into the detector's markers()), and where their
  // corners c0..c3 were found, px.
  std::array<int, kMaxSquaresInView> squares{};
  std::size_t square_count = 0;
  SquareCornerPixels corner_pixels = no_corner_pixels();
  double corner_rms = 0;  // metres, measured corners vs the fitted map squares
  std::array<DashPattern, 4> patterns{};  // sides of the first square, in measured order
  int solid_side = -1;
  std::uint32_t hypotheses_found = 0;   // square hypotheses that passed every check this frame
  std::uint32_t hypotheses_merged = 0;  // variants of one of those, not scored (traces_corner)
  std::uint16_t threshold = 0;  // of the strobe difference, this frame
  bool mask_from_shared_pass = false;  // the tape mask came from the pair's shared pass
  TapePointCounters points;
  HoughCounters hough;

  bool found() const { return outcome == SquareOutcome::found; }
};

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
  static constexpr double kMinPeriodRatio = 1.5;

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
  // (TapeMotionFitter, line_time: seconds a row). Not ok when not found, and under dof 6 (a tilt
  // skews the square as a drive does).
  TapeMotionFit fit_motion(const SquareDetection& detection, double line_time);
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
  // One hypothesis, identified: the map square and its corners c0..c3 on the ceiling plane.
  struct IdentifiedSquare {
    std::size_t square = 0;
    std::array<Eigen::Vector2d, 4> corners;
  };

  // detect() with the shared pass's runs, if any.
  SquareDetection detect_pair(const GrayImageView& on, const GrayImageView& off, const DifferenceNoise& noise,
                              const PairPass* pair, const RigidTransform* prior, const RowMotion* rows);
  // Scores candidates_ (evaluate()) into found_, found_fits_ and identified_ after the found
  // already there; returns how many there are then. With none, detection.outcome says why the
  // strongest did not pass (no_square: no candidate).
  std::size_t score_candidates(const RigidTransform* prior, std::size_t found, SquareDetection& detection);
  // A refined hypothesis that did not pass (failed_fits_), refitted with the other ridge of points
  // beside its sides (SquareRefiner::side_ridges): each choice of ridges for up to kMaxRidgeSides
  // sides, while ridge_refits_left_ lasts. Each that passes is added to found_; returns how many
  // there are then.
  std::size_t refit_on_other_ridges(const SquareFit& fit, const SquareDetection& detection, const RigidTransform* prior,
                                    std::size_t found);
  // One hypothesis, its sides refined: the dash pattern, which square; detection.outcome says why not.
  SquareDetection evaluate(const SquareFit& fit, SquareDetection detection, const RigidTransform* prior,
                           IdentifiedSquare& identified);
  // A hypothesis that passed with a loose fit (attempt, from fit as the last refine() left it,
  // identified as identified; corner RMS above kCloseFitCornerRms of the check's limit), posed again
  // on its straightened sides (SquareRefiner::straighten) when a side moves and the pose's
  // corners then fit the map's square at least twice as closely; else all unchanged.
  void pose_on_straight_sides(SquareFit& fit, SquareDetection& attempt, IdentifiedSquare& identified);
  // The dash patterns of the refined square (measured: its corners where the points were mapped;
  // points[k]: those that may lie on side k), which map square it is, its pose.
  using SidePoints = std::array<std::span<const Eigen::Vector2d>, 4>;
  SquareDetection classify(const SquareFit& fit, const std::array<Eigen::Vector2d, 4>& measured,
                           const SidePoints& points, const SquareDetection& detection,
                           const RigidTransform* prior, IdentifiedSquare& identified);
  // The pose from the corners of the squares seen, with the consistency checks and covariance.
  SquareDetection solve(std::span<const IdentifiedSquare> seen, SquareDetection detection) const;
  SquareDetection solve_tilted(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector3d> world,
                               std::span<const Eigen::Vector3d> bearings, SquareDetection detection) const;
  // The tail of both: on_ceiling (x-y in W of the corners, from the fitted pose) checked against
  // the map, the confidence, the covariance (unit_covariance times the corners' noise variance in
  // m^2), the squares and their corners' pixels.
  SquareDetection finish_pose(std::span<const IdentifiedSquare> seen, std::span<const Eigen::Vector2d> on_ceiling,
                              std::span<const Eigen::Vector2d> pixels, const Eigen::Matrix<double, 6, 6>& unit_covariance,
                              SquareDetection detection) const;
  // dof 6: the tilt of a refined quadrilateral; the frame's tape as a level camera at that tilt
  // would have mapped it (level_points()), and points carried there.
  bool probe_tilt(const std::array<Eigen::Vector2d, 4>& corners, RollPitchYaw& tilt) const;
  void level_view(const RollPitchYaw& tilt);
  Eigen::Vector2d levelled(const Eigen::Vector2d& point) const;
  std::array<Eigen::Vector2d, 4> levelled(const std::array<Eigen::Vector2d, 4>& corners) const;
  std::span<const Eigen::Vector2d> level_points() const { return {level_points_.data(), tape_points_.all().size()}; }

  SquareConfig config_;
  Dof dof_;
  // dof 6: the frame's tape points as a level camera at view_tilt_ maps them (metres), once
  // view_levelled_ this frame.
  std::vector<Eigen::Vector2d> level_points_;
  bool view_levelled_ = false;
  RollPitchYaw view_tilt_;
  Eigen::Matrix3d level_from_base_ = Eigen::Matrix3d::Identity();
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
  TapeMask tape_mask_;
  TapePoints tape_points_;
  TapeMotionFitter motion_fitter_;
  SquareRefiner refiner_;
  HoughLines hough_;
  HoughLineList peaks_;
  SquareCandidates candidates_;
  // The refined hypotheses that did not pass, this pair, in the order scored; the refits on other
  // ridges per frame (refit_on_other_ridges), and the sides one hypothesis tries.
  std::array<SquareFit, 2 * kMaxSquareCandidates> failed_fits_;
  std::size_t failed_count_ = 0;
  static constexpr int kMaxRidgeRefits = 8;
  static constexpr std::size_t kMaxRidgeSides = 3;
  int ridge_refits_left_ = 0;
  // The hypotheses that passed, this pair (of both searches under dof 6), their squares and fits.
  static constexpr std::size_t kMaxFound = 2 * kMaxSquareCandidates + kMaxRidgeRefits;
  std::array<SquareDetection, kMaxFound> found_;
  std::array<IdentifiedSquare, kMaxFound> identified_;
  std::array<SquareFit, kMaxFound> found_fits_;
  // The squares one hypothesis may be (evaluate()), one per map square at most.
  struct Option {
    IdentifiedSquare square;
    SquareDetection detection;
  };
  std::vector<Option> options_;
};

}  // namespace irloc
