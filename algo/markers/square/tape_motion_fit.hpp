#pragma once
// Under a rolling shutter with no motion known (a drive's first frame, a frame after a gap): the
// robot's motion within the frame, from the square's own tape. A tape point seen in image row v
// was mapped to the ceiling plane from the base frame at t_ns + v * line_time; carried into W by
// the pose at t_ns moved on by the motion (pose_after, algo/source/rolling_shutter.hpp) it lies
// on its side of the map square. The pose at t_ns (x, y, yaw) and the motion (velocity x, y in
// the heading frame, yaw rate) are fitted together to the points' distances from their sides,
// by Gauss-Newton from the plain fit and no motion (with a prior on the motion, the motion before
// a gap or the fastest robot's, a MAP estimate; motion_prior_terms.hpp). The points are averaged in short stretches of
// each side first (kBinsPerSide): the mean of the tape's pixels across its width is its centre
// line, so the stretches' scatter about their sides is the measurement's noise (not the tape's
// width), and the fit's standard deviations say how well the frame decides the motion. A square's
// sides span hundreds of rows: a turn bends them, a drive stretches or skews the square against
// its known side. A level robot (dof 3 and 4, the plane's scale at the fitted height). Fixed
// buffers; allocates nothing.

#include <array>
#include <cstddef>
#include <optional>
#include <span>

#include <Eigen/Core>

#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/source_input.hpp"

namespace irloc::square {

struct TapeMotionFit {
  bool ok = false;                 // false: too few points on the sides, or singular
  RigidTransform world_from_base;  // T_W_B at t_ns
  FrameMotion motion;
  // Standard deviations for the scatter of the points about their sides: the velocity's along
  // its worse axis (m/s), the yaw rate's (rad/s).
  double velocity_sigma = 0;
  double yaw_rate_sigma = 0;
  // Of (x, y, yaw) at t_ns, with the motion's uncertainty in it (m^2, m rad, rad^2).
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  std::size_t stretches = 0;  // stretches of sides fitted
};

// The tape as the detector saw it: camera-centred ceiling-plane points (TapePoints::all(),
// collected without a motion) and the image row of each.
struct SeenTape {
  std::span<const Eigen::Vector2d> points;
  std::span<const int> rows;
  Eigen::Vector2d camera_xy = Eigen::Vector2d::Zero();  // the plane's origin in the base frame
  double scale = 1;  // plane metres to metres at the robot's fitted height
};

class TapeMotionFitter {
 public:
  static constexpr std::size_t kMaxSquares = 2;
  static constexpr std::size_t kBinsPerSide = 64;  // 3 cm of a 2 m side, a little over half a tape width

  // squares: the corners c0..c3 (W, x-y) of the map squares seen, at most kMaxSquares; initial:
  // the plain fit (level); half_width: the tape's; line_time: seconds a row; prior: on the motion
  // (nullopt: the tape alone decides it).
  TapeMotionFit fit(const SeenTape& tape, std::span<const std::array<Eigen::Vector2d, 4>> squares, double half_width,
                    double line_time, const RigidTransform& initial, const std::optional<MotionPrior>& prior);

 private:
  struct Side {
    Eigen::Vector2d start, along, normal;  // W; unit vectors
    double length = 0;
  };
  // A stretch of a side: the mean of its tape points.
  struct Stretch {
    Eigen::Vector2d base = Eigen::Vector2d::Zero();  // in the base frame at the row time, metres
    double time = 0;                                 // seconds after t_ns
    std::size_t side = 0;
    int count = 0;
  };
  struct State {
    Eigen::Vector2d position;
    double yaw = 0;
    FrameMotion motion;
  };

  // The tape points that lie within gate of a side of the square at state, away from the
  // corners, averaged per stretch of their side.
  void assign(const SeenTape& tape, double line_time, const State& state, double gate, double corner_margin);
  // Gauss-Newton over the stretches (and the prior, when given) from state; normal: the stretches'
  // alone at the result. False when singular.
  bool solve(State& state, const std::optional<MotionPrior>& prior, Eigen::Matrix<double, 6, 6>& normal,
             double& cost) const;
  // A stretch's variance about its side that a cost over the stretches shows (six parameters).
  double stretch_variance(double cost) const { return cost / static_cast<double>(stretch_count_ - 6); }

  std::array<Stretch, 4 * kMaxSquares * kBinsPerSide> stretches_{};
  std::size_t stretch_count_ = 0;
  std::array<Side, 4 * kMaxSquares> sides_{};
  std::size_t side_count_ = 0;
};

}  // namespace irloc::square
