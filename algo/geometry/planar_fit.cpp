#include "algo/geometry/planar_fit.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "algo/core/static_vector.hpp"

namespace irloc {
namespace {

// Centroids and the sums sum(a . b), sum(a x b), sum(|a|^2) of the centred point sets.
struct CentredSums {
  Eigen::Vector2d from_centroid, to_centroid;
  double dot = 0, cross = 0, from_squared = 0;
};

bool centred_sums(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to, CentredSums& s) {
  if (from.size() != to.size() || from.size() < 2) return false;
  s.from_centroid.setZero();
  s.to_centroid.setZero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    s.from_centroid += from[i];
    s.to_centroid += to[i];
  }
  s.from_centroid /= static_cast<double>(from.size());
  s.to_centroid /= static_cast<double>(to.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d a = from[i] - s.from_centroid, b = to[i] - s.to_centroid;
    s.dot += a.dot(b);
    s.cross += a.x() * b.y() - a.y() * b.x();
    s.from_squared += a.squaredNorm();
  }
  return s.from_squared > 0 && std::hypot(s.dot, s.cross) > 0;
}

void finish(const CentredSums& s, double scale, PlanarTransform& fit) {
  fit.scale = scale;
  fit.yaw = std::atan2(s.cross, s.dot);
  const Eigen::Rotation2Dd rotation(fit.yaw);
  fit.translation = s.to_centroid - scale * (rotation * s.from_centroid);
}

}  // namespace

bool fit_rigid_2d(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to,
                  PlanarTransform& fit) {
  CentredSums sums;
  if (!centred_sums(from, to, sums)) return false;
  finish(sums, 1, fit);
  return true;
}

bool fit_similarity_2d(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to,
                       PlanarTransform& fit) {
  CentredSums sums;
  if (!centred_sums(from, to, sums)) return false;
  finish(sums, std::hypot(sums.dot, sums.cross) / sums.from_squared, fit);
  return true;
}

bool level_pose_from_ceiling(std::span<const Eigen::Vector3d> world_points,
                             std::span<const Eigen::Vector3d> bearings_c, double ceiling_z,
                             const RigidTransform& base_from_camera, Dof dof, RigidTransform& world_from_base) {
  if (dof == Dof::full6 || world_points.size() != bearings_c.size()) return false;
  const std::size_t count = std::min(world_points.size(), kMaxCeilingPoints);
  // Ray slopes (horizontal offset per metre of height) in the level base frame, and the points.
  StaticVector<Eigen::Vector2d, kMaxCeilingPoints> slopes, targets;
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d ray = base_from_camera.rotation * bearings_c[i];
    if (!(ray.z() > 0)) return false;
    slopes.push_back(ray.head<2>() / ray.z());
    targets.push_back(world_points[i].head<2>());
  }
  const Eigen::Vector2d camera_xy = base_from_camera.translation.head<2>();
  PlanarTransform fit;
  double height = 0;  // of the ceiling above the camera
  if (dof == Dof::planar3) {
    height = ceiling_z - base_from_camera.translation.z();
    if (!(height > 0)) return false;
    // Points in the base frame: camera position + height * slope.
    for (Eigen::Vector2d& slope : slopes) slope = camera_xy + height * slope;
    if (!fit_rigid_2d({slopes.begin(), slopes.end()}, {targets.begin(), targets.end()}, fit)) return false;
  } else {
    // world_xy = height R slope + (R camera_xy + t): a similarity whose scale is the height.
    if (!fit_similarity_2d({slopes.begin(), slopes.end()}, {targets.begin(), targets.end()}, fit)) return false;
    height = fit.scale;
    fit.translation -= Eigen::Rotation2Dd(fit.yaw) * camera_xy;
  }
  const double base_z = dof == Dof::planar3 ? 0 : ceiling_z - height - base_from_camera.translation.z();
  world_from_base.rotation = rotation_from_rpy(0, 0, fit.yaw);
  world_from_base.translation = Eigen::Vector3d(fit.translation.x(), fit.translation.y(), base_z);
  return true;
}

Eigen::Matrix<double, 6, 6> level_fit_covariance(std::span<const Eigen::Vector2d> points_in_base,
                                                  const Eigen::Vector2d& camera_xy, double height_above_camera,
                                                  double yaw, double sigma, Dof dof) {
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
  if (dof == Dof::full6 || points_in_base.size() < 2 || !(height_above_camera > 0)) return covariance;
  // Parameters (x, y, yaw, z); dof 3 uses the first three.
  const int n = dof == Dof::height4 ? 4 : 3;
  const Eigen::Matrix2d turn_derivative = (Eigen::Matrix2d() << -std::sin(yaw), -std::cos(yaw), std::cos(yaw),
                                           -std::sin(yaw)).finished();
  const Eigen::Matrix2d rotation = (Eigen::Matrix2d() << std::cos(yaw), -std::sin(yaw), std::sin(yaw), std::cos(yaw))
                                       .finished();
  Eigen::Matrix4d information = Eigen::Matrix4d::Zero();
  for (const Eigen::Vector2d& point : points_in_base) {
    Eigen::Matrix<double, 2, 4> jacobian;
    jacobian.col(0) = Eigen::Vector2d::UnitX();
    jacobian.col(1) = Eigen::Vector2d::UnitY();
    jacobian.col(2) = turn_derivative * point;
    jacobian.col(3) = -rotation * (point - camera_xy) / height_above_camera;
    information += jacobian.transpose() * jacobian;
  }
  Eigen::Matrix4d inverse = Eigen::Matrix4d::Zero();
  if (n == 4) {
    inverse = information.inverse();
  } else {
    inverse.topLeftCorner<3, 3>() = information.topLeftCorner<3, 3>().inverse();
  }
  inverse *= sigma * sigma;
  // (x, y, yaw, z) -> (x, y, z, roll, pitch, yaw).
  constexpr int kPoseIndex[4] = {0, 1, 5, 2};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) covariance(kPoseIndex[i], kPoseIndex[j]) = inverse(i, j);
  }
  return covariance;
}

}  // namespace irloc
