#include "algo/calibration/drive_adjustment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose_refinement.hpp"
#include "algo/geometry/rotation_vector.hpp"

namespace irloc::calibration {

std::array<bool, 6> pose_axes(Dof dof) {
  switch (dof) {
    case Dof::planar3: return {true, true, false, false, false, true};
    case Dof::height4: return {true, true, true, false, false, true};
    case Dof::full6: return {true, true, true, true, true, true};
  }
  return {};
}

std::string DriveAdjustment::global_name(int g) const {
  if (g < lenses_) return lens_parameter_name(input_.lens.model, g);
  static constexpr const char* kMount[] = {"mount roll", "mount pitch", "mount yaw", "mount x", "mount y", "mount z"};
  return kMount[g - lenses_];
}

void DriveAdjustment::set_up_parameters() {
  for (bool axis : axes_) pose_dim_ += axis ? 1 : 0;
  const CameraIntrinsics& lens = input_.lens;
  // Broad priors only keep the normal matrix invertible; they carry no information.
  for (int g = 0; g < lenses_; ++g) prior_sigma_[g] = g < 2 ? lens.fx : g < 4 ? lens.width : 10.0;
  for (int a = 0; a < 3; ++a) prior_sigma_[lenses_ + a] = std::numbers::pi;
  for (int a = 3; a < 6; ++a) prior_sigma_[lenses_ + a] = 10.0;

  const auto inform = [&](int g, double sigma, const std::string& why) {
    prior_sigma_[g] = sigma;
    informative_[static_cast<std::size_t>(g)] = true;
    prior_reason_[static_cast<std::size_t>(g)] = why;
  };
  const auto fix = [&](int g, const std::string& why) {
    fixed_[static_cast<std::size_t>(g)] = true;
    fixed_reason_[static_cast<std::size_t>(g)] = why;
  };
  char text[160];
  std::snprintf(text, sizeof text, "prior input +- %.3g px: shifts the image like a mount tilt", options_.principal_point_sigma_px);
  inform(2, options_.principal_point_sigma_px, text);
  inform(3, options_.principal_point_sigma_px, text);
  held_unless_observed_[2] = held_unless_observed_[3] = true;
  const int mount = lenses_;
  std::snprintf(text, sizeof text,
                "prior input +- %.3g m: no motion of a wheeled base shows where on its axle its origin lies",
                options_.mount_sigma_m);
  inform(mount + 4, options_.mount_sigma_m, text);
  if (options_.dof == Dof::planar3) {
    std::snprintf(text, sizeof text,
                  "prior input +- %.3g m: a ceiling seen face-on gives only focal length / height", options_.mount_sigma_m);
    inform(mount + 5, options_.mount_sigma_m, text);
  } else {
    fix(mount + 5, "every pose's z is estimated (dof 4/6): the mount's z is the same unknown");
    // With every pose's height free, nothing fixes the scale of focal length / height.
    std::snprintf(text, sizeof text,
                  "prior input +- %.3g %%: a ceiling seen face-on gives only focal length / height, and under dof 4/6 "
                  "every pose's height is free", 100 * options_.focal_length_sigma);
    inform(0, options_.focal_length_sigma * lens.fx, text);
  }
  if (options_.dof == Dof::full6) {
    fix(mount + 0, "every pose's roll is estimated (dof 6): a constant mount roll is the same unknown");
    fix(mount + 1, "every pose's pitch is estimated (dof 6): a constant mount pitch is the same unknown");
  }
}

int DriveAdjustment::free_globals() const {
  int count = 0;
  for (int g = 0; g < globals_; ++g) count += fixed_[static_cast<std::size_t>(g)] ? 0 : 1;
  return count;
}

double DriveAdjustment::global_value(const AdjustmentState& state, int g) const {
  if (g < lenses_) return lens_parameter(state.lens, g);
  const int a = g - lenses_;
  if (a < 3) return log_rotation(state.mount.rotation * input_.mount.rotation.transpose())[a];
  return state.mount.translation[a - 3];
}

void DriveAdjustment::reset_global(int g) {
  if (g < lenses_) {
    set_lens_parameter(state_.lens, g, lens_parameter(input_.lens, g));
    return;
  }
  const int a = g - lenses_;
  if (a < 3) {
    Eigen::Vector3d change = log_rotation(state_.mount.rotation * input_.mount.rotation.transpose());
    change[a] = 0;
    state_.mount.rotation = exp_rotation(change) * input_.mount.rotation;
  } else {
    state_.mount.translation[a - 3] = input_.mount.translation[a - 3];
  }
}

AdjustmentCost DriveAdjustment::evaluate(const AdjustmentState& state, NormalEquations* normal) const {
  AdjustmentCost result;
  if (normal) normal->reset(drive_.frames().size());
  add_reprojection(state, normal, result);
  add_lateral_slip(state, normal, result);
  add_priors(state, normal, result);
  return result;
}

void DriveAdjustment::add_reprojection(const AdjustmentState& state, NormalEquations* normal, AdjustmentCost& result) const {
  const std::span<const DriveFrame> frames = drive_.frames();
  const std::span<const PointObservation> dots = drive_.observations();
  const CameraModel camera(state.lens);
  const Eigen::Matrix3d camera_from_base = state.mount.rotation.transpose();
  const double inverse_variance = 1 / (pixel_sigma_ * pixel_sigma_);
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const RigidTransform& pose = state.poses[k];
    const Eigen::Matrix3d base_from_world = pose.rotation.transpose();
    for (std::size_t i = frames[k].first; i < frames[k].first + frames[k].count; ++i) {
      const Eigen::Vector3d relative = dots[i].world - pose.translation;
      const Eigen::Vector3d point_b = base_from_world * relative;
      const Eigen::Vector3d offset = point_b - state.mount.translation;
      const Eigen::Vector3d point_c = camera_from_base * offset;
      Eigen::Vector2d pixel;
      Eigen::Matrix<double, 2, 3> d_pixel_d_point;
      if (!camera.project(point_c, pixel, d_pixel_d_point)) continue;
      ++result.valid;
      const Eigen::Vector2d error = pixel - dots[i].pixel;
      const double norm = error.norm();
      const double weight = robust_weight(RobustLoss::huber, options_.loss_scale_px, norm);
      result.cost += robust_cost(RobustLoss::huber, options_.loss_scale_px, norm) * inverse_variance;
      result.weighted_sq += weight * norm * norm;
      if (!normal) continue;

      Eigen::Matrix<double, 2, kMaxGlobals> j_global = Eigen::Matrix<double, 2, kMaxGlobals>::Zero();
      j_global.leftCols<kMaxLensParameters>() = lens_jacobian(state.lens, point_c, pixel);
      const Eigen::Matrix<double, 2, 3> d_pixel_d_base = d_pixel_d_point * camera_from_base;
      j_global.block<2, 3>(0, lenses_) = d_pixel_d_base * skew(offset);
      j_global.block<2, 3>(0, lenses_ + 3) = -d_pixel_d_base;
      Eigen::Matrix<double, 2, 6> j_pose;
      const Eigen::Matrix<double, 2, 3> d_pixel_d_world = d_pixel_d_base * base_from_world;
      j_pose.leftCols<3>() = -d_pixel_d_world;
      j_pose.rightCols<3>() = d_pixel_d_world * skew(relative);

      const double w = weight * inverse_variance;
      normal->globals.noalias() += w * j_global.transpose() * j_global;
      normal->global_gradient.noalias() += w * j_global.transpose() * error;
      normal->poses[k].noalias() += w * j_pose.transpose() * j_pose;
      normal->crossing[k].noalias() += w * j_global.transpose() * j_pose;
      normal->pose_gradient[k].noalias() += w * j_pose.transpose() * error;
      normal->max_sensitivity = normal->max_sensitivity.cwiseMax(j_global.colwise().norm().transpose());
    }
  }
}

// The base does not slide sideways: consecutive positions differ along the mean heading only.
void DriveAdjustment::add_lateral_slip(const AdjustmentState& state, NormalEquations* normal, AdjustmentCost& result) const {
  const std::span<const DriveFrame> frames = drive_.frames();
  const double lateral_weight = 1 / (options_.lateral_slip_sigma_m * options_.lateral_slip_sigma_m);
  for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
    if (static_cast<double>(frames[k + 1].t_ns - frames[k].t_ns) * 1e-9 > options_.max_step_seconds) continue;
    const RigidTransform& a = state.poses[k];
    const RigidTransform& b = state.poses[k + 1];
    const double heading_a = heading(a);
    const double mean_heading = heading_a + 0.5 * wrap_angle(heading(b) - heading_a);
    const Eigen::Vector2d across(-std::sin(mean_heading), std::cos(mean_heading));
    const Eigen::Vector2d along(std::cos(mean_heading), std::sin(mean_heading));
    const Eigen::Vector2d displacement = (b.translation - a.translation).head<2>();
    const double error = across.dot(displacement);
    result.cost += lateral_weight * error * error;
    if (!normal) continue;
    Vector6 j_a = Vector6::Zero(), j_b = Vector6::Zero();
    j_a.head<2>() = -across;
    j_b.head<2>() = across;
    // d error / d mean heading = -along . displacement; each yaw moves the mean by half.
    j_a[5] = j_b[5] = -0.5 * along.dot(displacement);
    normal->poses[k].noalias() += lateral_weight * j_a * j_a.transpose();
    normal->poses[k + 1].noalias() += lateral_weight * j_b * j_b.transpose();
    normal->links[k].noalias() += lateral_weight * j_a * j_b.transpose();
    normal->pose_gradient[k] += lateral_weight * j_a * error;
    normal->pose_gradient[k + 1] += lateral_weight * j_b * error;
  }
}

void DriveAdjustment::add_priors(const AdjustmentState& state, NormalEquations* normal, AdjustmentCost& result) const {
  for (int g = 0; g < globals_; ++g) {
    const double residual = (global_value(state, g) - global_value(input_, g)) / prior_sigma_[g];
    result.cost += residual * residual;
    if (!normal) continue;
    normal->globals(g, g) += 1 / (prior_sigma_[g] * prior_sigma_[g]);
    normal->global_gradient[g] += residual / prior_sigma_[g];
  }
}

Eigen::SparseMatrix<double> DriveAdjustment::assemble(const NormalEquations& normal, double damping,
                                                      Eigen::VectorXd& rhs, const std::array<bool, kMaxGlobals>& held) const {
  std::array<int, kMaxGlobals> global_column{};
  int columns = 0;
  for (std::size_t g = 0; g < static_cast<std::size_t>(globals_); ++g) global_column[g] = fixed_[g] || held[g] ? -1 : columns++;
  std::array<int, 6> axis_offset{};
  int dim = 0;
  for (int a = 0; a < 6; ++a) axis_offset[static_cast<std::size_t>(a)] = axes_[static_cast<std::size_t>(a)] ? dim++ : -1;
  const std::size_t frames = normal.poses.size();
  const int size = columns + static_cast<int>(frames) * pose_dim_;
  const auto pose_column = [&](std::size_t k, int a) { return columns + static_cast<int>(k) * pose_dim_ + axis_offset[static_cast<std::size_t>(a)]; };

  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(columns * columns) + frames * static_cast<std::size_t>(pose_dim_ * (3 * pose_dim_ + 2 * columns)));
  rhs.setZero(size);
  const auto add = [&](int row, int column, double value, bool diagonal) {
    triplets.emplace_back(row, column, diagonal ? value * (1 + damping) : value);
  };
  for (int g = 0; g < globals_; ++g) {
    const int row = global_column[static_cast<std::size_t>(g)];
    if (row < 0) continue;
    rhs[row] = -normal.global_gradient[g];
    for (int h = 0; h < globals_; ++h) {
      const int column = global_column[static_cast<std::size_t>(h)];
      if (column >= 0) add(row, column, normal.globals(g, h), g == h);
    }
  }
  for (std::size_t k = 0; k < frames; ++k) {
    for (int a = 0; a < 6; ++a) {
      if (!axes_[static_cast<std::size_t>(a)]) continue;
      const int row = pose_column(k, a);
      rhs[row] = -normal.pose_gradient[k][a];
      for (int b = 0; b < 6; ++b) {
        if (!axes_[static_cast<std::size_t>(b)]) continue;
        add(row, pose_column(k, b), normal.poses[k](a, b), a == b);
        if (k + 1 < frames && normal.links[k](a, b) != 0) {
          add(row, pose_column(k + 1, b), normal.links[k](a, b), false);
          add(pose_column(k + 1, b), row, normal.links[k](a, b), false);
        }
      }
      for (int g = 0; g < globals_; ++g) {
        const int column = global_column[static_cast<std::size_t>(g)];
        if (column < 0) continue;
        add(row, column, normal.crossing[k](g, a), false);
        add(column, row, normal.crossing[k](g, a), false);
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(size, size);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  return matrix;
}

bool DriveAdjustment::step(const NormalEquations& normal, double damping, AdjustmentState& next) const {
  Eigen::VectorXd rhs;
  const Eigen::SparseMatrix<double> matrix = assemble(normal, damping, rhs);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::VectorXd delta = solver.solve(rhs);
  if (solver.info() != Eigen::Success || !delta.allFinite()) return false;
  next = state_;
  int column = 0;
  for (int g = 0; g < globals_; ++g) {
    if (fixed_[static_cast<std::size_t>(g)]) continue;
    const double d = delta[column++];
    if (g < lenses_) {
      set_lens_parameter(next.lens, g, lens_parameter(next.lens, g) + d);
    } else if (g < lenses_ + 3) {
      next.mount.rotation = exp_rotation(Eigen::Vector3d::Unit(g - lenses_) * d) * next.mount.rotation;
    } else {
      next.mount.translation[g - lenses_ - 3] += d;
    }
  }
  if (next.lens.fx <= 0 || next.lens.fy <= 0) return false;
  for (RigidTransform& pose : next.poses) {
    Vector6 d = Vector6::Zero();
    for (int a = 0; a < 6; ++a) {
      if (axes_[static_cast<std::size_t>(a)]) d[a] = delta[column++];
    }
    pose.translation += d.head<3>();
    pose.rotation = exp_rotation(d.tail<3>()) * pose.rotation;
  }
  return true;
}

int DriveAdjustment::solve() {
  NormalEquations normal;
  AdjustmentCost current = evaluate(state_, &normal);
  double damping = 1e-4;
  int iteration = 0;
  for (; iteration < options_.max_iterations; ++iteration) {
    AdjustmentState next;
    bool improved = false;
    while (damping < 1e8) {
      if (step(normal, damping, next)) {
        const AdjustmentCost trial = evaluate(next, nullptr);
        if (trial.valid >= current.valid && trial.cost <= current.cost) {
          const bool converged = current.cost - trial.cost <= 1e-10 * current.cost;
          state_ = std::move(next);
          current = evaluate(state_, &normal);
          damping = std::max(damping / 4, 1e-9);
          improved = !converged;
          break;
        }
      }
      damping *= 8;
    }
    if (!improved) break;
  }
  return iteration;
}

GlobalMatrix DriveAdjustment::global_covariance(const NormalEquations& normal, const std::array<bool, kMaxGlobals>& held) const {
  GlobalMatrix covariance = GlobalMatrix::Zero();
  Eigen::VectorXd rhs;
  const Eigen::SparseMatrix<double> matrix = assemble(normal, 0, rhs, held);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  if (solver.info() != Eigen::Success) return GlobalMatrix::Constant(std::numeric_limits<double>::infinity());
  std::array<int, kMaxGlobals> column{};
  int columns = 0;
  for (std::size_t g = 0; g < static_cast<std::size_t>(globals_); ++g) column[g] = fixed_[g] || held[g] ? -1 : columns++;
  for (int g = 0; g < globals_; ++g) {
    if (column[static_cast<std::size_t>(g)] < 0) continue;
    Eigen::VectorXd unit = Eigen::VectorXd::Zero(matrix.rows());
    unit[column[static_cast<std::size_t>(g)]] = 1;
    const Eigen::VectorXd covariance_column = solver.solve(unit);
    for (int h = 0; h < globals_; ++h) {
      if (column[static_cast<std::size_t>(h)] >= 0) covariance(h, g) = covariance_column[column[static_cast<std::size_t>(h)]];
    }
  }
  return covariance;
}

int DriveAdjustment::fix_by_motion(double driven_m, double turned_rad) {
  int views = 0;
  const RigidTransform* last_view = nullptr;
  for (const RigidTransform& pose : input_.poses) {
    if (last_view && (pose.translation - last_view->translation).head<2>().norm() < options_.view_spacing_m &&
        std::abs(wrap_angle(heading(pose) - heading(*last_view))) < options_.view_spacing_rad) {
      continue;
    }
    last_view = &pose;
    ++views;
  }
  char text[160];
  const int mount = lenses_;
  const auto fix = [&](int g) {
    if (fixed_[static_cast<std::size_t>(g)]) return;
    fixed_[static_cast<std::size_t>(g)] = true;
    fixed_reason_[static_cast<std::size_t>(g)] = text;
  };
  if (turned_rad < options_.min_turn_rad) {
    std::snprintf(text, sizeof text, "not observable on this drive: it turned %.0f deg (the mount's x needs %.0f deg of turning)",
                  turned_rad * 180 / std::numbers::pi, options_.min_turn_rad * 180 / std::numbers::pi);
    fix(mount + 3);
  }
  if (driven_m < options_.min_drive_m) {
    std::snprintf(text, sizeof text, "not observable on this drive: it drove %.2f m (the mount's yaw needs %.2f m of driving)",
                  driven_m, options_.min_drive_m);
    fix(mount + 2);
  }
  return views;
}

double DriveAdjustment::change_chi2(const GlobalMatrix& covariance) const {
  std::array<int, kMaxGlobals> free{};
  int count = 0;
  for (int g = 0; g < globals_; ++g) {
    if (!fixed_[static_cast<std::size_t>(g)]) free[static_cast<std::size_t>(count++)] = g;
  }
  Eigen::MatrixXd sub(count, count);
  Eigen::VectorXd change(count);
  for (int i = 0; i < count; ++i) {
    change[i] = global_value(state_, free[static_cast<std::size_t>(i)]) - global_value(input_, free[static_cast<std::size_t>(i)]);
    for (int j = 0; j < count; ++j) sub(i, j) = covariance(free[static_cast<std::size_t>(i)], free[static_cast<std::size_t>(j)]);
  }
  const Eigen::LDLT<Eigen::MatrixXd> factor(sub);
  if (factor.info() != Eigen::Success) return 0;
  return change.dot(factor.solve(change));
}

ResidualStats DriveAdjustment::residual_stats(const AdjustmentState& state, bool after, std::vector<DotResidual>& residuals) const {
  ResidualStats stats;
  const CameraModel camera(state.lens);
  const RigidTransform camera_from_base = state.mount.inverse();
  const std::span<const DriveFrame> frames = drive_.frames();
  const std::span<const PointObservation> dots = drive_.observations();
  std::vector<double> norms;
  double sum_sq = 0;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const RigidTransform camera_from_world = camera_from_base * state.poses[k].inverse();
    for (std::size_t i = frames[k].first; i < frames[k].first + frames[k].count; ++i) {
      Eigen::Vector2d pixel;
      DotResidual& residual = residuals[i];
      residual.pixel = dots[i].pixel;
      if (!camera.project(camera_from_world * dots[i].world, pixel)) continue;
      (after ? residual.after : residual.before) = pixel - dots[i].pixel;
      const double norm = (pixel - dots[i].pixel).norm();
      norms.push_back(norm);
      sum_sq += norm * norm;
      stats.max_px = std::max(stats.max_px, norm);
    }
  }
  stats.count = norms.size();
  if (!norms.empty()) {
    stats.rms_px = std::sqrt(sum_sq / static_cast<double>(norms.size()));
    std::nth_element(norms.begin(), norms.begin() + static_cast<std::ptrdiff_t>(norms.size() / 2), norms.end());
    stats.median_px = norms[norms.size() / 2];
  }
  return stats;
}

}  // namespace irloc::calibration
