#pragma once
// The fixed camera's pose over the floor from its intrinsics and four floor points of known
// position (config `camera.floor_reference`: a tile or any rectangle on the floor z = 0).
//
// The four pixels are undistorted to normalized coordinates, the floor-to-image homography is
// solved from them (DLT), and decomposed into the camera pose (H ~ [r1 r2 t]). Start-up only.
#include <array>
#include <string>
#include <Eigen/Core>
#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc {

struct FloorReference {
  std::array<Eigen::Vector2d, 4> world;   // corners on the floor, W metres, in order around the rectangle
  std::array<Eigen::Vector2d, 4> pixels;  // the same corners in the image, px, same order
};

struct FloorGeometry {
  bool ok = false;
  std::string error;                  // why not, naming the check that failed (start-up only)
  RigidTransform camera_from_world;   // T_C_W
  double reprojection_rms_px = 0;     // of the four corners
};

// Checks that the world corners form a rectangle (opposite sides and diagonals equal within 2 %,
// sides at least 5 cm), that the pixels form a convex quadrilateral inside the image, that the
// camera ends up above the floor, and that the corners reproject within 3 px.
FloorGeometry solve_floor_geometry(const CameraIntrinsics& camera, const FloorReference& reference);

}  // namespace irloc
