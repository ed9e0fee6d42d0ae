// The per-pixel ceiling table against the lens model run the other way (project).

#include <gtest/gtest.h>

#include <cmath>

#include "algo/markers/square/ceiling_plane_map.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

TEST(CeilingPlaneMap, EveryStoredPointProjectsBackToItsPixel) {
  const CameraIntrinsics intrinsics = fisheye(320, 256);
  const CameraModel camera(intrinsics);
  const Eigen::Isometry3d mount = up_mount();
  const double height = 2.0;
  const CeilingPlaneMap plane(camera, to_rigid(mount), height, 1.2);
  int checked = 0;
  for (int y = 0; y < plane.height(); y += 3) {
    for (int x = 0; x < plane.width(); x += 3) {
      const PlanePoint p = plane.row(y)[x];
      if (p.x == CeilingPlaneMap::kNoPoint) continue;
      // The stored point is relative to the camera centre, in base axes, at the ceiling.
      const Eigen::Vector3d in_base(p.x / kPlaneRawPerMetre, p.y / kPlaneRawPerMetre, height);
      const Eigen::Vector3d in_camera = mount.linear().transpose() * in_base;
      Eigen::Vector2d pixel;
      ASSERT_TRUE(camera.project(in_camera, pixel));
      // Rounding to 1/256 cm moves the point by < 0.03 mm: far below a pixel.
      EXPECT_NEAR(pixel.x(), x, 0.01);
      EXPECT_NEAR(pixel.y(), y, 0.01);
      // And the ray is within the configured angle from the vertical.
      EXPECT_LE(std::atan2(in_base.head<2>().norm(), height), 1.2 + 1e-3);
      ++checked;
    }
  }
  EXPECT_GT(checked, 2000);
  // The footprint straight up is height / f metres per pixel.
  EXPECT_NEAR(plane.min_metres_per_pixel(), height / intrinsics.fx, 0.02 * height / intrinsics.fx);
}

TEST(CeilingPlaneMap, RaysBeyondTheAngleAreNotMapped) {
  const CameraModel camera(fisheye(320, 256));
  const CeilingPlaneMap plane(camera, to_rigid(up_mount()), 2.0, 0.5);
  // The image corner looks ~90 degrees off axis; the centre straight up.
  EXPECT_EQ(plane.row(0)[0].x, CeilingPlaneMap::kNoPoint);
  EXPECT_NE(plane.row(128)[160].x, CeilingPlaneMap::kNoPoint);
  EXPECT_LE(plane.max_radius(), 2.0 * std::tan(0.5) + 1e-6);
}

}  // namespace
}  // namespace irloc::test
