#pragma once
// Calibrations shared by the geometry tests: one realistic lens of each model.

#include "algo/geometry/camera_intrinsics.hpp"

namespace irloc::test {

inline CameraIntrinsics make_intrinsics(LensModel model, int width, int height, double fx, double fy,
                                        std::array<double, 5> distortion) {
  CameraIntrinsics intrinsics;
  intrinsics.width = width;
  intrinsics.height = height;
  intrinsics.fx = fx;
  intrinsics.fy = fy;
  intrinsics.cx = 0.5 * (width - 1) + 3.25;  // off-centre on purpose
  intrinsics.cy = 0.5 * (height - 1) - 2.5;
  intrinsics.model = model;
  intrinsics.distortion = distortion;
  return intrinsics;
}

// A normal-angle lens with moderate barrel distortion and tangential terms.
inline CameraIntrinsics plumb_bob_lens() {
  return make_intrinsics(LensModel::plumb_bob, 640, 480, 520, 515, {-0.28, 0.09, 1e-3, -5e-4, -0.01});
}
// A wide-angle lens (about 110 degrees across the diagonal) with strong distortion.
inline CameraIntrinsics wide_plumb_bob_lens() {
  return make_intrinsics(LensModel::plumb_bob, 640, 480, 400, 401, {-0.3, 0.08, -2e-3, 1e-3, -0.005});
}
// A fisheye seeing beyond 90 degrees in the image corners.
inline CameraIntrinsics equidistant_lens() {
  return make_intrinsics(LensModel::equidistant, 1280, 800, 380, 381, {-0.01, 0.005, -0.002, 0.0003, 0});
}
// The square-marker paper's fisheye, also beyond 90 degrees in the corners.
inline CameraIntrinsics equisolid_lens() {
  return make_intrinsics(LensModel::equisolid, 640, 480, 220, 221, {0, 0, 0, 0, 0});
}

}  // namespace irloc::test
