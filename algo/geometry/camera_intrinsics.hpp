#pragma once
// The numbers of a calibrated camera, as read from a ROS camera_info file.

#include <array>

namespace irloc {

// Lens models of the calibration contract (docs/formats.md).
enum class LensModel {
  plumb_bob,    // OpenCV pinhole + Brown-Conrady: k1, k2, p1, p2, k3
  equidistant,  // OpenCV fisheye (Kannala-Brandt): k1, k2, k3, k4
  equisolid,    // r = 2 f sin(theta / 2), no coefficients
};

struct CameraIntrinsics {
  int width = 0;   // pixels
  int height = 0;  // pixels
  double fx = 0, fy = 0, cx = 0, cy = 0;  // pixels; (cx, cy) from the centre of pixel (0, 0)
  LensModel model = LensModel::plumb_bob;
  std::array<double, 5> distortion{};  // in the model's order, unused entries zero
};

}  // namespace irloc
