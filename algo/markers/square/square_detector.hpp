#pragma once
// The square tape marker path: a strobe pair in, the robot pose from the map's square out.
//
//   tape mask (difference, threshold, thin lines) -> ceiling plane points (per-pixel table)
//   -> Hough on the plane -> square hypotheses (search) -> for each: least-squares sides and
//   corners -> solid side by its dash pattern -> c0..c3 (cross-product test) -> planar rigid fit
//   (similarity for dof 4) -> consistency checks -> confidence; the best hypothesis, if it is
//   clearly better than any at another pose.
//
// Everything is sized in the constructor (start-up); detect() allocates nothing and its work is
// bounded by the point capacity and the Hough peak list (overflows are counted).

#include <array>
#include <cstdint>
#include <string_view>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/difference_noise.hpp"
#include "algo/kernels/hough_lines.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/dash_pattern.hpp"
#include "algo/markers/square/side_refinement.hpp"
#include "algo/markers/square/square_config.hpp"
#include "algo/markers/square/square_search.hpp"
#include "algo/markers/square/tape_mask.hpp"
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
};
std::string_view to_string(SquareOutcome outcome);

struct SquareDetection {
  SquareOutcome outcome = SquareOutcome::no_square;
  RigidTransform world_from_base;  // T_W_B when found
  double confidence = 0;           // in [0, 1]
  // Of (x, y, z, roll, pitch, yaw) of T_W_B, from the fit of the four corners (level_fit_covariance).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  // Where corners c0..c3 were found, px.
  std::array<Eigen::Vector2d, 4> corner_pixels{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero(),
                                               Eigen::Vector2d::Zero()};
  double corner_rms = 0;  // metres, measured corners vs the fitted map square
  std::array<DashPattern, 4> patterns{};  // sides in measured order
  int solid_side = -1;
  std::uint32_t hypotheses_found = 0;  // square hypotheses that passed every check this frame
  std::uint16_t threshold = 0;  // of the strobe difference, this frame
  TapePointCounters points;
  HoughCounters hough;

  bool found() const { return outcome == SquareOutcome::found; }
};

class SquareDetector {
 public:
  // pixel_bits: of the camera's frames (8: 8-bit frames; more: 16-bit ones). Throws
  // std::invalid_argument for dof 6, or a marker that is not a level square above the camera.
  SquareDetector(const CameraIntrinsics& camera, int pixel_bits, const RigidTransform& base_from_camera, Dof dof,
                 const SquareMarker& marker, const SquareConfig& config);

  // Its stages keep references to its members: it stays where it was made.
  SquareDetector(const SquareDetector&) = delete;
  SquareDetector& operator=(const SquareDetector&) = delete;

  // on, off: one strobe pair of the calibrated size and the depth set up (else outcome
  // bad_frames); noise: the pair's shared noise estimate (algo/kernels/difference_noise.hpp),
  // from which the tape threshold is derived unless the config fixes one.
  SquareDetection detect(const GrayImageView& on, const GrayImageView& off, const DifferenceNoise& noise);
  // The stages after the tape mask (a 0/255 mask of the frame region whose top-left pixel is
  // (x0, y0)), for tests and benchmarks.
  SquareDetection detect_in_mask(ImageView8 mask, int x0, int y0);
  const CeilingPlaneMap& plane() const { return plane_; }

  const SquareMarker& marker() const { return marker_; }
  double side() const { return side_; }
  int element_radius() const { return element_radius_; }

 private:
  // One hypothesis: refined sides, then solve().
  SquareDetection evaluate(const SquareSides& sides, SquareDetection detection) const;
  SquareDetection solve(const SquareFit& fit, SquareDetection detection) const;

  SquareConfig config_;
  Dof dof_;
  SquareMarker marker_;
  RigidTransform base_from_camera_;
  double side_ = 0;       // d from the map, metres
  double ceiling_z_ = 0;  // of the marker in W
  double map_turn_ = 0;   // turn(c0, c1, c2) of the map
  int element_radius_ = 0;
  std::uint32_t min_side_points_ = 0;
  CameraModel camera_;
  CeilingPlaneMap plane_;
  TapeMask tape_mask_;
  TapePoints tape_points_;
  HoughLines hough_;
  HoughLineList peaks_;
  SquareCandidates candidates_;
};

}  // namespace irloc
