#include "algo/source/pose_motion_fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include <Eigen/Cholesky>

#include "algo/geometry/pose_refinement.hpp"
#include "algo/source/motion_prior_terms.hpp"
#include "algo/source/rolling_shutter.hpp"

namespace irloc {

namespace {

constexpr int kMaxParameters = 9;  // six pose parameters and three of motion
using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxParameters, 1>;
using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxParameters, kMaxParameters>;
constexpr int kIterations = 10;
// Converged once a step moved the state by less than this many of its standard deviations (at
// min_pixel_sigma, the least noise the fit assumes): step^T J^T J step <= (kStopStepSigmas sigma)^2.
constexpr double kStopStepSigmas = 1e-3;

// The free pose parameters of the dof, indices into (x, y, z, roll, pitch, yaw).
std::span<const int> free_pose_parameters(Dof dof) {
  static constexpr std::array<int, 3> planar{0, 1, 5};
  static constexpr std::array<int, 4> height{0, 1, 2, 5};
  static constexpr std::array<int, 6> full{0, 1, 2, 3, 4, 5};
  switch (dof) {
    case Dof::planar3: return planar;
    case Dof::height4: return height;
    case Dof::full6: break;
  }
  return full;
}

struct State {
  PoseParameters pose;
  FrameMotion motion;
};

// The state moved by step: the free pose parameters first, then velocity x, y and yaw rate.
State stepped(const State& state, std::span<const int> free, const Vector& step) {
  State next = state;
  for (std::size_t i = 0; i < free.size(); ++i) next.pose[free[i]] += step[static_cast<Eigen::Index>(i)];
  const auto m = static_cast<Eigen::Index>(free.size());
  next.motion.velocity.x() += step[m];
  next.motion.velocity.y() += step[m + 1];
  next.motion.yaw_rate += step[m + 2];
  return next;
}

// A state with its pose at t_ns as a transform (made once per state, not once per point).
struct PosedState {
  RigidTransform world_from_base;
  FrameMotion motion;
};

PosedState posed(const State& state) { return {pose_from_parameters(state.pose), state.motion}; }

// Where the camera at its row's time sees world.
bool predicted(const PosedState& state, const Eigen::Vector3d& world, double row_time, const CameraModel& camera,
               const RigidTransform& base_from_camera, Eigen::Vector2d& pixel) {
  const RigidTransform world_from_camera = pose_after(state.world_from_base, row_time, state.motion) * base_from_camera;
  return camera.project(world_from_camera.inverse() * world, pixel);
}

// The observations the fit explains.
struct Observations {
  std::span<const Eigen::Vector3d> world;
  std::span<const Eigen::Vector2d> pixels;
  std::span<const double> row_times;
  const CameraModel& camera;
  const RigidTransform& base_from_camera;
};

// The normal equations J^T J and J^T r of the state (forward differences of `steps`) and the cost
// r^T r; false when a point is not in front of the camera.
bool linearize(const Observations& seen, const State& state, std::span<const int> free, const Vector& steps,
               Matrix& normal, Vector& gradient, double& cost) {
  const Eigen::Index n = steps.size();
  normal.setZero();
  gradient = Vector::Zero(n);
  cost = 0;
  const PosedState current = posed(state);
  std::array<PosedState, kMaxParameters> nudged;  // the state with parameter j stepped
  for (Eigen::Index j = 0; j < n; ++j) {
    Vector unit = Vector::Zero(n);
    unit[j] = steps[j];
    nudged[static_cast<std::size_t>(j)] = posed(stepped(state, free, unit));
  }
  for (std::size_t k = 0; k < seen.world.size(); ++k) {
    Eigen::Vector2d at;
    if (!predicted(current, seen.world[k], seen.row_times[k], seen.camera, seen.base_from_camera, at)) return false;
    Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, kMaxParameters> jacobian(2, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::Vector2d moved;
      if (!predicted(nudged[static_cast<std::size_t>(j)], seen.world[k], seen.row_times[k], seen.camera,
                     seen.base_from_camera, moved)) {
        return false;
      }
      jacobian.col(j) = (moved - at) / steps[j];
    }
    normal += jacobian.transpose() * jacobian;
    gradient += jacobian.transpose() * (seen.pixels[k] - at);
    cost += (seen.pixels[k] - at).squaredNorm();
  }
  return true;
}

// The pixels' variance a cost over 2 points - parameters residuals shows, at least min_pixel_sigma^2.
double variance_of(double cost, std::size_t points, Eigen::Index parameters, double min_pixel_sigma) {
  const double redundancy = static_cast<double>(2 * points) - static_cast<double>(parameters);
  return std::max(redundancy > 0 ? cost / redundancy : 0.0, min_pixel_sigma * min_pixel_sigma);
}

// The pixels' noise as the fit's residuals show it (the a-posteriori variance factor), at least
// min_pixel_sigma; empty when a point is not in front of the camera.
std::optional<double> pixel_variance(const Observations& seen, const State& state, Eigen::Index parameters,
                                     double min_pixel_sigma) {
  double cost = 0;
  const PosedState final_state = posed(state);
  for (std::size_t k = 0; k < seen.world.size(); ++k) {
    Eigen::Vector2d at;
    if (!predicted(final_state, seen.world[k], seen.row_times[k], seen.camera, seen.base_from_camera, at)) {
      return std::nullopt;
    }
    cost += (seen.pixels[k] - at).squaredNorm();
  }
  return variance_of(cost, seen.world.size(), parameters, min_pixel_sigma);
}

}  // namespace

PoseMotionFit fit_pose_and_motion(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector2d> pixels,
                                  std::span<const double> row_times, const CameraModel& camera,
                                  const RigidTransform& base_from_camera, const RigidTransform& initial, Dof dof,
                                  double min_pixel_sigma, const std::optional<MotionPrior>& motion_prior) {
  PoseMotionFit fit;
  const std::span<const int> free = free_pose_parameters(dof);
  const auto n = static_cast<Eigen::Index>(free.size() + 3);
  if (2 * world.size() < static_cast<std::size_t>(n)) return fit;
  const Observations seen{world, pixels, row_times, camera, base_from_camera};
  const FrameMotion prior_mean = motion_prior ? motion_prior->mean : FrameMotion{};
  State state{parameters_from_pose(constrain_pose(initial, dof)), prior_mean};
  // Forward differences: pose in metres and radians, velocity in m/s (over milliseconds).
  Vector steps(n);
  for (std::size_t i = 0; i < free.size(); ++i) steps[static_cast<Eigen::Index>(i)] = 1e-7;
  steps.tail(3) = Eigen::Vector3d(1e-4, 1e-4, 1e-4);
  Matrix normal(n, n);
  Vector gradient(n);
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    double cost = 0;
    if (!linearize(seen, state, free, steps, normal, gradient, cost)) return fit;
    // The prior in the normal equations' units (pixels squared): weighed by the pixel noise the
    // residuals show, it pulls the motion toward its mean as the frame fails to show it.
    Matrix system = normal;
    if (motion_prior) {
      const double residual_variance = variance_of(cost, world.size(), n, min_pixel_sigma);
      add_motion_prior(*motion_prior, state.motion, residual_variance, system, gradient);
    }
    const Eigen::LDLT<Matrix> solver(system);
    if (solver.info() != Eigen::Success || !solver.isPositive()) return fit;
    const Vector step = solver.solve(gradient);
    if (!step.allFinite()) return fit;
    state = stepped(state, free, step);
    const double step_bound = kStopStepSigmas * min_pixel_sigma;
    if (step.dot(system * step) <= step_bound * step_bound) break;
  }
  const std::optional<double> variance = pixel_variance(seen, state, n, min_pixel_sigma);
  if (!variance) return fit;
  const Matrix identity = Matrix::Identity(n, n);
  Matrix joint = normal;
  if (motion_prior) joint.diagonal().tail(3) += *variance * motion_prior_information(*motion_prior);
  const Matrix covariance = Eigen::LDLT<Matrix>(joint).solve(identity) * *variance;
  const Eigen::Index m = n - 3;
  fit.velocity_sigma = std::sqrt(std::max(covariance(m, m), covariance(m + 1, m + 1)));
  fit.yaw_rate_sigma = std::sqrt(covariance(m + 2, m + 2));
  const Matrix given_motion = Eigen::LDLT<Matrix>(normal.topLeftCorner(m, m)).solve(Matrix::Identity(m, m)) * *variance;
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      fit.motion_pose_covariance(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]) =
          covariance(i, j) - given_motion(i, j);
    }
  }
  fit.world_from_base = pose_from_parameters(state.pose);
  fit.motion = state.motion;
  fit.ok = std::isfinite(fit.velocity_sigma) && std::isfinite(fit.yaw_rate_sigma);
  return fit;
}

}  // namespace irloc
