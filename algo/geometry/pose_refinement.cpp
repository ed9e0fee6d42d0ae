#include "algo/geometry/pose_refinement.hpp"

#include <array>
#include <cmath>
#include <span>

#include <Eigen/Cholesky>

namespace irloc {
namespace {

// Derivative matrices of the elementary rotations.
Eigen::Matrix3d rx(double a, bool derivative) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d m;
  if (derivative) m << 0, 0, 0, 0, -s, -c, 0, c, -s;
  else m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}
Eigen::Matrix3d ry(double a, bool derivative) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d m;
  if (derivative) m << -s, 0, c, 0, 0, 0, -c, 0, -s;
  else m << c, 0, s, 0, 1, 0, -s, 0, c;
  return m;
}
Eigen::Matrix3d rz(double a, bool derivative) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix3d m;
  if (derivative) m << -s, -c, 0, c, -s, 0, 0, 0, 0;
  else m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

// The parameters a dof estimates (indices into x, y, z, roll, pitch, yaw). The fit works in
// their space only: the Jacobian holds their columns, the normal equations their rows.
constexpr std::array<int, 3> kPlanar3Columns = {0, 1, 5};
constexpr std::array<int, 4> kHeight4Columns = {0, 1, 2, 5};
constexpr std::array<int, 6> kFull6Columns = {0, 1, 2, 3, 4, 5};

std::span<const int> free_columns(Dof dof) {
  switch (dof) {
    case Dof::planar3: return kPlanar3Columns;
    case Dof::height4: return kHeight4Columns;
    case Dof::full6: break;
  }
  return kFull6Columns;
}

template <int kFree>
struct Linearization {
  bool ok = false;
  double cost = 0, squared_error_sum = 0;
  Eigen::Matrix<double, kFree, kFree> normal = Eigen::Matrix<double, kFree, kFree>::Zero();  // J^T W J
  Eigen::Matrix<double, kFree, 1> gradient = Eigen::Matrix<double, kFree, 1>::Zero();       // J^T W r
};

// The cost and its normal equations at p.
template <auto columns>
Linearization<static_cast<int>(columns.size())> linearize(std::span<const Eigen::Vector3d> world_points,
                                                         std::span<const Eigen::Vector2d> pixels,
                                                         const CameraModel& camera,
                                                         const RigidTransform& base_from_camera,
                                                         const PoseParameters& p, const RefinementOptions& options) {
  constexpr int kFree = static_cast<int>(columns.size());
  Linearization<kFree> result;
  const Eigen::Matrix3d r_x = rx(p(3), false), r_y = ry(p(4), false), r_z = rz(p(5), false);
  const Eigen::Matrix3d rotation = r_z * r_y * r_x;  // R_W_B
  // d R / d (roll, pitch, yaw), for the free angles
  std::array<Eigen::Matrix3d, 3> d_rotation;
  for (const int column : columns) {
    if (column == 3) d_rotation[0] = r_z * r_y * rx(p(3), true);
    if (column == 4) d_rotation[1] = r_z * ry(p(4), true) * r_x;
    if (column == 5) d_rotation[2] = rz(p(5), true) * r_y * r_x;
  }
  const Eigen::Matrix3d camera_from_base = base_from_camera.rotation.transpose();
  const Eigen::Vector3d translation = p.head<3>();
  for (std::size_t i = 0; i < world_points.size(); ++i) {
    const Eigen::Vector3d relative = world_points[i] - translation;
    const Eigen::Vector3d point_b = rotation.transpose() * relative;
    const Eigen::Vector3d point_c = camera_from_base * (point_b - base_from_camera.translation);
    Eigen::Vector2d predicted;
    Eigen::Matrix<double, 2, 3> d_pixel_d_point;
    if (!camera.project(point_c, predicted, d_pixel_d_point)) return result;
    const Eigen::Vector2d residual = predicted - pixels[i];
    const double error = residual.norm();
    result.squared_error_sum += error * error;
    result.cost += robust_cost(options.loss, options.loss_scale_px, error);
    // d point_b / d parameters: -R^T for the translation, (dR/da)^T relative for the angles.
    Eigen::Matrix<double, 3, kFree> d_point_b;
    for (int f = 0; f < kFree; ++f) {
      const int column = columns[static_cast<std::size_t>(f)];
      if (column < 3) d_point_b.col(f) = -rotation.transpose().col(column);
      else d_point_b.col(f) = d_rotation[static_cast<std::size_t>(column - 3)].transpose() * relative;
    }
    const Eigen::Matrix<double, 2, kFree> jacobian = d_pixel_d_point * camera_from_base * d_point_b;
    const double weight = robust_weight(options.loss, options.loss_scale_px, error);
    result.normal.noalias() += weight * jacobian.transpose() * jacobian;
    result.gradient.noalias() += weight * jacobian.transpose() * residual;
  }
  result.ok = true;
  return result;
}

}  // namespace

// Robust weight of a point with reprojection error e (pixels), and its cost.
double robust_weight(RobustLoss loss, double scale, double error) {
  switch (loss) {
    case RobustLoss::none: return 1;
    case RobustLoss::huber: return error <= scale ? 1 : scale / error;
    case RobustLoss::cauchy: return 1 / (1 + (error / scale) * (error / scale));
  }
  return 1;
}
double robust_cost(RobustLoss loss, double scale, double error) {
  switch (loss) {
    case RobustLoss::none: return error * error;
    case RobustLoss::huber: return error <= scale ? error * error : 2 * scale * error - scale * scale;
    case RobustLoss::cauchy: return scale * scale * std::log1p((error / scale) * (error / scale));
  }
  return error * error;
}

PoseParameters parameters_from_pose(const RigidTransform& world_from_base) {
  const RollPitchYaw rpy = rpy_from_rotation(world_from_base.rotation);
  PoseParameters p;
  p << world_from_base.translation, rpy.roll, rpy.pitch, rpy.yaw;
  return p;
}

RigidTransform pose_from_parameters(const PoseParameters& p) {
  return {rotation_from_rpy(p(3), p(4), p(5)), p.head<3>()};
}

RigidTransform constrain_pose(const RigidTransform& world_from_base, Dof dof) {
  const PoseParameters p = parameters_from_pose(world_from_base);
  PoseParameters constrained = PoseParameters::Zero();
  for (const int column : free_columns(dof)) constrained(column) = p(column);
  return pose_from_parameters(constrained);
}

namespace {

// Levenberg-Marquardt over the free parameters (columns) from p, the others held.
template <auto columns>
PoseFit refine_free(std::span<const Eigen::Vector3d> world_points, std::span<const Eigen::Vector2d> pixels,
                    const CameraModel& camera, const RigidTransform& base_from_camera, PoseParameters p,
                    const RefinementOptions& options) {
  constexpr int kFree = static_cast<int>(columns.size());
  using Vector = Eigen::Matrix<double, kFree, 1>;
  using Matrix = Eigen::Matrix<double, kFree, kFree>;
  PoseFit fit;
  const auto relinearize = [&](const PoseParameters& at) {
    return linearize<columns>(world_points, pixels, camera, base_from_camera, at, options);
  };
  Linearization<kFree> current = relinearize(p);
  if (!current.ok) return fit;
  double damping = 1e-4;
  int iteration = 0;
  for (; iteration < options.max_iterations; ++iteration) {
    Matrix system = current.normal;
    for (int k = 0; k < kFree; ++k) system(k, k) *= 1 + damping;
    const Vector step = -system.ldlt().solve(current.gradient);
    if (!step.allFinite()) break;
    PoseParameters candidate = p;
    for (int k = 0; k < kFree; ++k) candidate(columns[static_cast<std::size_t>(k)]) += step(k);
    const Linearization<kFree> next = relinearize(candidate);
    if (next.ok && next.cost <= current.cost) {
      const double step_bound = options.stop_step_sigmas * options.pixel_sigma;
      const bool converged = current.cost - next.cost <= 1e-12 * current.cost + 1e-18 ||
                             step.norm() <= 1e-12 * (1 + p.norm()) ||
                             (step_bound > 0 && step.dot(system * step) <= step_bound * step_bound);
      p = candidate;
      current = next;
      damping = std::max(damping * 0.1, 1e-9);
      if (converged) break;
    } else {
      damping *= 10;
      if (damping > 1e8) break;
    }
  }
  // The weights and Jacobian the covariance is made of are current's, made at p, unless wrapping
  // the yaw moves p: then they are made again at the wrapped p.
  const double yaw = wrap_angle(p(5));
  if (yaw != p(5)) {
    p(5) = yaw;
    current = relinearize(p);
    if (!current.ok) return fit;
  }
  const Matrix inverse = current.normal.ldlt().solve(Matrix::Identity());
  for (int r = 0; r < kFree; ++r) {
    for (int c = 0; c < kFree; ++c) {
      fit.covariance(columns[static_cast<std::size_t>(r)], columns[static_cast<std::size_t>(c)]) =
          options.pixel_sigma * options.pixel_sigma * inverse(r, c);
    }
  }
  fit.ok = fit.covariance.allFinite();
  fit.world_from_base = pose_from_parameters(p);
  fit.rms_px = std::sqrt(current.squared_error_sum / static_cast<double>(world_points.size()));
  fit.cost = current.cost;
  fit.iterations = iteration;
  return fit;
}

}  // namespace

PoseFit refine_pose(std::span<const Eigen::Vector3d> world_points, std::span<const Eigen::Vector2d> pixels,
                    const CameraModel& camera, const RigidTransform& base_from_camera,
                    const RigidTransform& initial_world_from_base, const RefinementOptions& options) {
  const int free_count = static_cast<int>(options.dof);
  if (world_points.size() != pixels.size() || 2 * static_cast<int>(world_points.size()) < free_count) return {};
  const PoseParameters p = parameters_from_pose(constrain_pose(initial_world_from_base, options.dof));
  switch (options.dof) {
    case Dof::planar3:
      return refine_free<kPlanar3Columns>(world_points, pixels, camera, base_from_camera, p, options);
    case Dof::height4:
      return refine_free<kHeight4Columns>(world_points, pixels, camera, base_from_camera, p, options);
    case Dof::full6: break;
  }
  return refine_free<kFull6Columns>(world_points, pixels, camera, base_from_camera, p, options);
}

}  // namespace irloc
