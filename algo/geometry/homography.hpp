#pragma once
// The homography between two planes from point correspondences (normalized DLT, Hartley & Zisserman
// 4.4, solved as least squares with h33 = 1), for a marker's dots or a floor reference's points:
// at most 64 pairs, no heap.

#include <span>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace irloc {

// H with to ~ H * (from, 1), from n >= 4 pairs of which no 3 of the first 4 need be special, but
// the set must not be collinear. false when the fit is degenerate. from.size() == to.size() <= 64.
bool fit_homography(std::span<const Eigen::Vector2d> from, std::span<const Eigen::Vector2d> to, Eigen::Matrix3d& h);

// H applied to a 2-D point.
inline Eigen::Vector2d apply_homography(const Eigen::Matrix3d& h, const Eigen::Vector2d& point) {
  const Eigen::Vector3d mapped = h * point.homogeneous();
  return mapped.hnormalized();
}

}  // namespace irloc
