#include "algo/markers/square/tape_motion_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "algo/geometry/pose.hpp"
#include "algo/source/motion_prior_terms.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc::square {

namespace {

constexpr int kIterations = 10;
// The first assignment is to the plain fit, whose sides the rolling shutter bends and shifts by
// up to the travel within the frame (a centimetre or two at the fastest robot); the second, to
// the fitted pose and motion, keeps the tape and its blur.
constexpr double kFirstGate = 0.02;   // m beyond the tape's half width
constexpr double kSecondGate = 0.005;  // m
// Fewest stretches of sides for a fit of six parameters to be worth its sigmas, and fewest tape
// points in a stretch (a stretch cut by a dash's end or the gate still spans the tape's width).
constexpr std::size_t kMinStretches = 24;
constexpr int kMinStretchPoints = 4;

Eigen::Matrix2d turn_by(double angle) { return Eigen::Rotation2Dd(angle).toRotationMatrix(); }

// The perpendicular of v (a quarter turn left).
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

}  // namespace

void TapeMotionFitter::assign(const SeenTape& tape, double line_time, const State& state, double gate,
                              double corner_margin) {
  for (std::size_t s = 0; s < side_count_ * kBinsPerSide; ++s) stretches_[s] = Stretch{};
  const Eigen::Matrix2d heading = turn_by(state.yaw);
  int row = -1;
  RigidTransform then;
  for (std::size_t i = 0; i < tape.points.size(); ++i) {
    const Eigen::Vector2d base = tape.camera_xy + tape.scale * tape.points[i];
    const double time = tape.rows[i] * line_time;
    if (tape.rows[i] != row) {  // the points come row by row
      row = tape.rows[i];
      then = pose_after(RigidTransform{}, time, state.motion);
    }
    const Eigen::Vector2d world =
        state.position + heading * (then.rotation.topLeftCorner<2, 2>() * base + then.translation.head<2>());
    double nearest = gate;
    std::size_t found = side_count_;
    double found_along = 0;
    for (std::size_t s = 0; s < side_count_; ++s) {
      const Side& side = sides_[s];
      const double along = side.along.dot(world - side.start);
      const double distance = std::abs(side.normal.dot(world - side.start));
      if (along < corner_margin || along > side.length - corner_margin || distance > nearest) continue;
      nearest = distance;
      found = s;
      found_along = along;
    }
    if (found == side_count_) continue;
    const auto bin = std::min(kBinsPerSide - 1, static_cast<std::size_t>(found_along / sides_[found].length * kBinsPerSide));
    Stretch& stretch = stretches_[found * kBinsPerSide + bin];
    stretch.base += base;
    stretch.time += time;
    stretch.side = found;
    ++stretch.count;
  }
  // The stretches seen, their means, packed to the front.
  stretch_count_ = 0;
  for (std::size_t s = 0; s < side_count_ * kBinsPerSide; ++s) {
    Stretch stretch = stretches_[s];
    if (stretch.count < kMinStretchPoints) continue;
    stretch.base /= stretch.count;
    stretch.time /= stretch.count;
    stretches_[stretch_count_++] = stretch;
  }
}

bool TapeMotionFitter::solve(State& state, const std::optional<MotionPrior>& prior, Eigen::Matrix<double, 6, 6>& normal,
                             double& cost) const {
  for (int iteration = 0; iteration <= kIterations; ++iteration) {
    normal.setZero();
    Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
    cost = 0;
    const Eigen::Matrix2d heading = turn_by(state.yaw);
    for (std::size_t k = 0; k < stretch_count_; ++k) {
      const Stretch& point = stretches_[k];
      const double time = point.time;
      const RigidTransform then = pose_after(RigidTransform{}, time, state.motion);
      const Side& side = sides_[point.side];
      // The point in the base frame at t_ns (the motion's turn and travel since), then in W.
      const Eigen::Matrix2d turn = then.rotation.topLeftCorner<2, 2>();
      const Eigen::Vector2d travel = then.translation.head<2>();
      const Eigen::Vector2d turned = turn * point.base;
      const Eigen::Vector2d local = turned + travel;
      const double residual = side.normal.dot(state.position + heading * local - side.start);
      // Its derivatives by x, y, yaw, velocity x, y and yaw rate (the chord's change with the turn,
      // of second order over a frame, left out).
      const Eigen::Vector2d normal_local = heading.transpose() * side.normal;
      const Eigen::Matrix2d halfway = turn_by(state.motion.yaw_rate * time / 2);
      Eigen::Matrix<double, 6, 1> row;
      row << side.normal.x(), side.normal.y(), normal_local.dot(perp(local)),
          time * normal_local.dot(halfway.col(0)), time * normal_local.dot(halfway.col(1)),
          time * normal_local.dot(perp(travel / 2 + turned));
      normal += row * row.transpose();
      gradient -= row * residual;
      cost += residual * residual;
    }
    if (iteration == kIterations) break;  // the normal matrix and cost at the last state
    Eigen::Matrix<double, 6, 6> system = normal;
    if (prior) add_motion_prior(*prior, state.motion, stretch_variance(cost), system, gradient);
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solver(system);
    if (solver.info() != Eigen::Success || !solver.isPositive()) return false;
    const Eigen::Matrix<double, 6, 1> step = solver.solve(gradient);
    if (!step.allFinite()) return false;
    state.position += step.head<2>();
    state.yaw += step[2];
    state.motion.velocity.x() += step[3];
    state.motion.velocity.y() += step[4];
    state.motion.yaw_rate += step[5];
    if (step.head<3>().norm() < 1e-8 && step.tail<3>().norm() < 1e-6) {
      iteration = kIterations - 1;  // converged: once more for the normal matrix at the result
    }
  }
  return true;
}

TapeMotionFit TapeMotionFitter::fit(const SeenTape& tape, std::span<const std::array<Eigen::Vector2d, 4>> squares,
                                    double half_width, double line_time, const RigidTransform& initial,
                                    const std::optional<MotionPrior>& prior) {
  TapeMotionFit result;
  side_count_ = 0;
  for (std::size_t q = 0; q < std::min(squares.size(), kMaxSquares); ++q) {
    for (std::size_t k = 0; k < 4; ++k) {
      const Eigen::Vector2d start = squares[q][k], end = squares[q][(k + 1) % 4];
      const double length = (end - start).norm();
      const Eigen::Vector2d along = (end - start) / length;
      sides_[side_count_++] = {start, along, perp(along), length};
    }
  }
  // From no motion, as the plain fit was found (the first assignment's gate is about it), also
  // with a prior.
  State state{initial.translation.head<2>(), rpy_from_rotation(initial.rotation).yaw, FrameMotion{}};
  Eigen::Matrix<double, 6, 6> normal;
  double cost = 0;
  for (const double gate : {kFirstGate, kSecondGate}) {
    assign(tape, line_time, state, half_width + gate, 2 * half_width + gate);
    if (stretch_count_ < kMinStretches || !solve(state, prior, normal, cost)) return result;
  }
  // The stretches' scatter about their sides stands for their noise.
  const double variance = stretch_variance(cost);
  if (prior) normal.diagonal().tail(3) += variance * motion_prior_information(*prior);
  const Eigen::Matrix<double, 6, 6> covariance =
      Eigen::LDLT<Eigen::Matrix<double, 6, 6>>(normal).solve(Eigen::Matrix<double, 6, 6>::Identity()) * variance;
  result.velocity_sigma = std::sqrt(std::max(covariance(3, 3), covariance(4, 4)));
  result.yaw_rate_sigma = std::sqrt(covariance(5, 5));
  result.pose_covariance = covariance.topLeftCorner<3, 3>();
  result.world_from_base = initial;
  result.world_from_base.rotation = Eigen::AngleAxisd(state.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  result.world_from_base.translation.head<2>() = state.position;
  result.motion = state.motion;
  result.stretches = stretch_count_;
  result.ok = std::isfinite(result.velocity_sigma) && std::isfinite(result.yaw_rate_sigma);
  return result;
}

}  // namespace irloc::square
