#pragma once
// The intrinsics of each lens model as a parameter vector for estimation, and the derivative of a
// projected pixel with respect to each of them (analytic; the projection itself and its
// derivative with respect to the point are CameraModel's).
//
// Parameter order: fx, fy, cx, cy, then the model's distortion coefficients in the order of its
// camera_info file: plumb_bob k1, k2, p1, p2, k3; equidistant k1, k2, k3, k4; equisolid none.

#include <Eigen/Core>

#include "algo/geometry/camera_intrinsics.hpp"

namespace irloc::calibration {

inline constexpr int kMaxLensParameters = 9;
using LensJacobian = Eigen::Matrix<double, 2, kMaxLensParameters>;

int lens_parameter_count(LensModel model);
// "fx", "fy", "cx", "cy", "k1", ...; index < lens_parameter_count(model).
const char* lens_parameter_name(LensModel model, int index);
double lens_parameter(const CameraIntrinsics& intrinsics, int index);
void set_lens_parameter(CameraIntrinsics& intrinsics, int index, double value);

// d pixel / d parameter at a point in camera coordinates that CameraModel projected to `pixel`
// with these intrinsics. Columns beyond the model's count are zero.
LensJacobian lens_jacobian(const CameraIntrinsics& intrinsics, const Eigen::Vector3d& point_c,
                           const Eigen::Vector2d& pixel);

}  // namespace irloc::calibration
