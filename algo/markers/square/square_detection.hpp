#pragma once
// What the square path reports of a strobe pair (SquareDetector::detect): the pose, or why none.

#include <array>
#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/hough_lines.hpp"
#include "algo/markers/square/dash_pattern.hpp"
#include "algo/markers/square/square_outcome.hpp"
#include "algo/markers/square/tape_points.hpp"

namespace irloc::square {

// Squares fused into one pose when they are seen together.
inline constexpr std::size_t kMaxSquaresInView = 2;
using SquareCornerPixels = std::array<std::array<Eigen::Vector2d, 4>, kMaxSquaresInView>;
inline SquareCornerPixels no_corner_pixels() {
  SquareCornerPixels pixels;
  for (auto& square : pixels) square.fill(Eigen::Vector2d::Zero());
  return pixels;
}

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

}  // namespace irloc::square
