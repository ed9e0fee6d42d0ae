#pragma once
// The share of a sighting's error that every sighting of its marker repeats (docs/survey.md, "The
// error every sighting of a marker repeats"). A dot's centroid error is partly fixed by where the
// dot falls on the pixel grid across the direction of travel: a straight line keeps that place for
// the whole pass, and the way back (the camera turned half a turn) repeats it in the marker's
// frame. The part of it that the marker's pose fit absorbs (a shift, turn or scale of the whole
// pattern: a height error) moves every sighting of the marker alike: no number of sightings on
// that line averages it out, and the residuals show only the rest of it.
//
// Measured from the drive: each dot's residuals, turned into its marker's level frame, keep a
// mean over the run; how far those means scatter beyond their own noise is the fixed part, pooled
// over every dot, and share() is its variance over the noise's (the dots' scatter about their own
// means). A fit of N dots to 4 parameters keeps the same fraction, (2N - 4) / 2N, of both in its
// residuals (each independent per dot), so the ratio is that of the dots' errors themselves: the
// share of a sighting's covariance that the fixed part gives. A drive that sees a marker from
// several lines or a curved path averages the fixed parts into those means, and measures the
// smaller share that its estimates keep.
// Memory: one entry per graph node and cell, sized at start-up; no heap per frame.

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/survey/marker_sighting.hpp"

namespace irloc::survey {

class MarkerBias {
 public:
  explicit MarkerBias(std::size_t nodes) : dots_(nodes) {}  // allocates

  // A sighting of node's marker; level_from_camera_2d turns the image's axes into the marker's
  // level frame (the camera's turn about the vertical at that sighting).
  void add(int node, const MarkerSighting& sighting, const Eigen::Matrix2d& level_from_camera_2d);
  // Fixed variance over the pixel variance, in [0, 1]; 0 until measured.
  double share() const;

 private:
  struct DotSums {
    Eigen::Vector2f sum = Eigen::Vector2f::Zero();  // of its residuals in the marker's level frame, px
    float squares = 0;                              // of their squared norms, px^2
    int count = 0;
  };
  struct Contribution {  // one dot's share of the pooled sums
    double within = 0, mean_squares = 0, inverse_count = 0;
    int degrees = 0, dots = 0;
  };
  static Contribution contribution(const DotSums& dot);
  void pool(const Contribution& contribution, double sign);

  std::vector<std::array<DotSums, dot::kCellCount>> dots_;
  double within_ = 0;         // sum over dots of their squared residuals about their own mean, px^2
  int within_degrees_ = 0;    // 2 (n - 1) summed
  double mean_squares_ = 0;   // sum over dots of their mean's squared norm, px^2
  double inverse_counts_ = 0; // sum over dots of 2 / n (the noise a mean keeps, in units of the pixel variance)
  int pooled_dots_ = 0;       // dots seen at least twice
};

}  // namespace irloc::survey
