#pragma once
// The default board's camera (rpi4-noir: IMX219 binned to 820 x 616) looking up from a robot, for
// the rolling-shutter tests.

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::test {

inline CameraIntrinsics board_camera() {
  CameraIntrinsics k;
  k.width = 820;
  k.height = 616;
  k.fx = k.fy = 679.7;
  k.cx = 409.5;
  k.cy = 307.5;
  k.model = LensModel::plumb_bob;
  return k;
}

// Camera up, image top toward the front, 0.3 m above the base and 5 cm ahead.
inline RigidTransform up_mount() {
  RigidTransform mount;
  mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation = {0.05, 0, 0.3};
  return mount;
}

}  // namespace irloc::test
