#pragma once
// Rotations as rotation vectors (axis times angle, rad), the increments of the least-squares
// solvers: R <- exp(d) R.

#include <Eigen/Core>

namespace irloc {

// The cross-product matrix: skew(a) * b == a.cross(b).
Eigen::Matrix3d skew(const Eigen::Vector3d& v);

// The rotation of a rotation vector (first order below 1e-15 rad).
Eigen::Matrix3d exp_rotation(const Eigen::Vector3d& v);

// The rotation vector of a rotation, angle in [0, pi].
Eigen::Vector3d log_rotation(const Eigen::Matrix3d& r);

}  // namespace irloc
