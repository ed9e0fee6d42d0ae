#include "algo/geometry/homography.hpp"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

namespace irloc {
namespace {

// Similarity moving the points' centroid to the origin and their mean distance to sqrt(2).
Eigen::Matrix3d normalizing_transform(std::span<const Eigen::Vector2d> points) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double mean_distance = 0;
  for (const Eigen::Vector2d& p : points) mean_distance += (p - centroid).norm();
  mean_distance /= static_cast<double>(points.size());
  const double s = mean_distance > 0 ? std::sqrt(2.0) / mean_distance : 1.0;
  Eigen::Matrix3d t;
  t << s, 0, -s * centroid.x(), 0, s, -s * centroid.y(), 0, 0, 1;
  return t;
}

}  // namespace

bool fit_homography(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to, Eigen::Matrix3d& h) {
  if (from.size() != to.size() || from.size() < 4 || from.size() > 64) return false;
  const Eigen::Matrix3d t_from = normalizing_transform(from);
  const Eigen::Matrix3d t_to = normalizing_transform(to);
  // Sum of a_k a_k^T over the two DLT rows a_k of each pair: the 9 x 9 normal matrix.
  Eigen::Matrix<double, 9, 9> normal = Eigen::Matrix<double, 9, 9>::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector3d p = t_from * from[i].homogeneous();
    const Eigen::Vector3d q = t_to * to[i].homogeneous();
    Eigen::Matrix<double, 9, 1> row_u = Eigen::Matrix<double, 9, 1>::Zero();
    Eigen::Matrix<double, 9, 1> row_v = Eigen::Matrix<double, 9, 1>::Zero();
    row_u.segment<3>(0) = q.z() * p;
    row_u.segment<3>(6) = -q.x() * p;
    row_v.segment<3>(3) = q.z() * p;
    row_v.segment<3>(6) = -q.y() * p;
    normal.noalias() += row_u * row_u.transpose();
    normal.noalias() += row_v * row_v.transpose();
  }
  // With h33 = 1 (the from points' centroid, the normalized origin, maps to a finite point, as
  // for any plane seen in front of a camera) the DLT is linear least squares in the other eight:
  // the normal matrix's leading 8 x 8 block times them is minus its last column. A singular block
  // (a pivot below 1e-12 of the largest) means the points do not fix H.
  const Eigen::LDLT<Eigen::Matrix<double, 8, 8>> solver(normal.topLeftCorner<8, 8>());
  const Eigen::Matrix<double, 8, 1> pivots = solver.vectorD().cwiseAbs();
  if (solver.info() != Eigen::Success || !(pivots.minCoeff() > 1e-12 * pivots.maxCoeff())) return false;
  const Eigen::Matrix<double, 8, 1> v = solver.solve(-normal.topRightCorner<8, 1>());
  Eigen::Matrix3d normalized_h;
  normalized_h << v(0), v(1), v(2), v(3), v(4), v(5), v(6), v(7), 1;
  h = t_to.inverse() * normalized_h * t_from;
  if (std::abs(h(2, 2)) < 1e-300) return false;
  h /= h(2, 2);
  return std::isfinite(h.sum());
}

}  // namespace irloc
