#pragma once
// The pixel error that every sighting of a marker repeats (docs/survey.md, "The error every
// sighting of a marker repeats"). A dot's centroid error is partly fixed by where the dot falls on
// the pixel grid across the direction of travel: a straight line keeps that place for the whole
// pass, and the way back (the camera turned half a turn) repeats it in the marker's frame. The
// part of it that the marker's pose fit absorbs (a shift, turn or scale of the whole pattern: a
// height error) moves every sighting of the marker alike: no number of sightings on that line
// averages it out, and the residuals show only the rest of it. It lies across the line: along
// it the place changes from one sighting to the next and the error alternates.
//
// Measured from the drive, per image axis: each dot's residuals keep a mean over the run in the
// image's axes, folded so that the way back (the camera turned by more than a quarter turn from
// the marker's first sighting) adds its error with the sign it has in the marker's frame. How far
// those means scatter beyond their own noise, pooled over every dot, is the fixed error's 2 x 2
// covariance in the image's axes (fixed_covariance()). A fit of N dots to 4 parameters keeps the
// same fraction, (2N - 4) / 2N, of both in its residuals (each independent per dot), so it is that
// of the dots' errors themselves. A drive that sees a marker from several lines or a curved path
// averages the fixed parts into those means, and measures the smaller error its estimates keep.
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
  explicit MarkerBias(std::size_t nodes) : dots_(nodes), first_heading_(nodes, Eigen::Vector2f::Zero()) {}  // allocates

  // A sighting of node's marker; level_from_camera_2d turns the image's axes into the marker's
  // level frame (the camera's turn about the vertical at that sighting).
  void add(int node, const MarkerSighting& sighting, const Eigen::Matrix2d& level_from_camera_2d);
  // px^2 in the image's axes (u, v); positive semi-definite, each of its variances at most the
  // pixel noise's; zero until measured.
  Eigen::Matrix2d fixed_covariance() const;

 private:
  struct DotSums {
    Eigen::Vector2f sum = Eigen::Vector2f::Zero();  // of its folded residuals, px
    Eigen::Vector3f squares = Eigen::Vector3f::Zero();  // of their products uu, vv, uv, px^2
    int count = 0;
  };
  struct Contribution {  // one dot's share of the pooled sums
    Eigen::Matrix2d within = Eigen::Matrix2d::Zero(), mean_squares = Eigen::Matrix2d::Zero();
    double inverse_count = 0;
    int degrees = 0, dots = 0;
  };
  static Contribution contribution(const DotSums& dot);
  void pool(const Contribution& contribution, double sign);

  std::vector<std::array<DotSums, dot::kCellCount>> dots_;
  std::vector<Eigen::Vector2f> first_heading_;  // per node: its first sighting's image u axis in its level frame
  Eigen::Matrix2d within_ = Eigen::Matrix2d::Zero();  // sum over dots of their residuals' scatter about their mean, px^2
  int within_degrees_ = 0;                            // n - 1 summed
  Eigen::Matrix2d mean_squares_ = Eigen::Matrix2d::Zero();  // sum over dots of their mean's outer product, px^2
  double inverse_counts_ = 0;  // sum over dots of 1 / n (the noise a mean keeps, in units of the pixel variance)
  int pooled_dots_ = 0;        // dots seen at least twice
};

}  // namespace irloc::survey
