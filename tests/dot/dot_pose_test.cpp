// The dot pose stage on decoded markers made here: three markers seen by a pinhole camera from a
// known pose, their pixels projected by the camera model. refit_dot_pose (the fit again after the
// markers' world points moved a little, as a rolling shutter's points moved to t_ns for a better
// motion) must give what solve_dot_pose gives on the moved points, with the same markers left out,
// and must take a marker back in when it fits again.

#include <cmath>

#include <gtest/gtest.h>

#include "algo/markers/dot/dot_pose.hpp"
#include "tests/dot/dot_scene.hpp"

namespace irloc::dot {
namespace {

constexpr std::array<int, 3> kIds = {1234, 421, 3003};

DotPoseOptions options() {
  DotPoseOptions result;
  result.refinement.dof = Dof::planar3;
  return result;
}

struct MarkerScene {
  CameraModel camera{test::pinhole_camera()};
  RigidTransform base_from_camera = to_rigid(test::up_mount({0.1, 0.0, 0.3}));
  RigidTransform world_from_base = to_rigid(test::level_pose(0.2, -0.1, 0.3));
  MarkerObservationList markers;

  MarkerScene() {
    const std::array<Eigen::Vector3d, 3> origins = {Eigen::Vector3d(0.3, -0.2, 2.6), Eigen::Vector3d(-0.4, 0.1, 2.6),
                                                    Eigen::Vector3d(0.5, 0.6, 2.6)};
    const RigidTransform camera_from_world = (world_from_base * base_from_camera).inverse();
    for (std::size_t m = 0; m < kIds.size(); ++m) {
      const DotMarker mapped{kIds[m], origins[m], 0.4 * static_cast<double>(m)};
      MarkerObservation marker;
      marker.id = mapped.id;
      const CellMask cells = cells_from_id(mapped.id);
      for (int cell = 0; cell < kCellCount; ++cell) {
        if ((cells & (1u << cell)) == 0) continue;
        const std::size_t k = marker.dot_count++;
        marker.cells[k] = static_cast<std::uint8_t>(cell);
        marker.world[k] = cell_in_world(mapped, cell);
        EXPECT_TRUE(camera.project(camera_from_world * marker.world[k], marker.pixels[k]));
        // A few hundredths of a pixel of noise, the same in every run.
        marker.pixels[k] += 0.03 * Eigen::Vector2d(std::sin(7.0 * k + m), std::cos(5.0 * k + 3 * m));
        marker.centre_pixel += marker.pixels[k];
      }
      marker.centre_pixel /= marker.dot_count;
      markers.push_back(marker);
    }
  }

  std::span<MarkerObservation> span() { return {markers.begin(), markers.size()}; }

  // The last fit as solve_dot_pose leaves it when it used every marker but the last.
  DotPoseResult solve_without_last() {
    const DotPoseResult fit = solve_dot_pose(span().first(markers.size() - 1), camera, base_from_camera, options());
    markers.back().used = false;
    return fit;
  }

  void shift_last(double dx) {
    for (std::size_t k = 0; k < markers.back().dot_count; ++k) markers.back().pixels[k].x() += dx;
  }

  // Every marker's world points moved as a rolling shutter's correction moves them: by up to a
  // couple of millimetres, growing with the image row.
  void move_points() {
    for (MarkerObservation& marker : markers) {
      for (std::size_t k = 0; k < marker.dot_count; ++k) marker.world[k].x() += 4e-6 * marker.pixels[k].y();
    }
  }
};

TEST(DotPoseRefit, GivesTheFullSolveOfTheMovedPoints) {
  MarkerScene scene;
  const DotPoseResult first = solve_dot_pose(scene.span(), scene.camera, scene.base_from_camera, options());
  ASSERT_TRUE(first.fit.ok);
  ASSERT_EQ(first.markers_used, 3);
  EXPECT_LT((first.fit.world_from_base.translation - scene.world_from_base.translation).norm(), 2e-4);
  scene.move_points();
  const DotPoseResult refit = refit_dot_pose(scene.span(), scene.camera, scene.base_from_camera, options(), first,
                                             first.fit.world_from_base);
  MarkerScene copy = scene;
  const DotPoseResult full = solve_dot_pose(copy.span(), copy.camera, copy.base_from_camera, options());
  ASSERT_TRUE(refit.fit.ok);
  ASSERT_TRUE(full.fit.ok);
  // The moved points moved the pose (by about a millimetre) ...
  EXPECT_GT((refit.fit.world_from_base.translation - first.fit.world_from_base.translation).norm(), 5e-4);
  // ... to the minimum the full solve finds, with its covariance and markers.
  EXPECT_LT((refit.fit.world_from_base.translation - full.fit.world_from_base.translation).norm(), 1e-7);
  EXPECT_NEAR(rpy_from_rotation(refit.fit.world_from_base.rotation).yaw,
              rpy_from_rotation(full.fit.world_from_base.rotation).yaw, 1e-8);
  EXPECT_NEAR(refit.fit.cost, full.fit.cost, 1e-9 * (1 + full.fit.cost));
  EXPECT_NEAR(refit.fit.covariance(0, 0), full.fit.covariance(0, 0), 1e-6 * full.fit.covariance(0, 0));
  EXPECT_EQ(refit.markers_used, 3);
  EXPECT_EQ(refit.reference_marker, full.reference_marker);
}

TEST(DotPoseRefit, AfterAMarkerWasLeftOutSolvesInFull) {
  MarkerScene scene;
  scene.shift_last(30);  // a marker moved on the ceiling
  const DotPoseResult last = scene.solve_without_last();
  ASSERT_TRUE(last.fit.ok);
  scene.move_points();
  MarkerScene copy = scene;
  const DotPoseResult refit =
      refit_dot_pose(scene.span(), scene.camera, scene.base_from_camera, options(), last, last.fit.world_from_base);
  const DotPoseResult full = solve_dot_pose(copy.span(), copy.camera, copy.base_from_camera, options());
  ASSERT_EQ(refit.fit.ok, full.fit.ok);
  EXPECT_EQ(refit.markers_used, full.markers_used);
  EXPECT_EQ(refit.reference_marker, full.reference_marker);
  for (std::size_t m = 0; m < scene.markers.size(); ++m) EXPECT_EQ(scene.markers[m].used, copy.markers[m].used) << m;
  EXPECT_EQ((refit.fit.world_from_base.translation - full.fit.world_from_base.translation).norm(), 0.0);
}

TEST(DotPoseRefit, TakesBackAMarkerThatFitsAgain) {
  MarkerScene scene;
  // Left out of the last fit (as a rolling shutter's distortion can leave a marker out before the
  // points are moved for the motion); it fits the refit's pose.
  const DotPoseResult last = scene.solve_without_last();
  ASSERT_TRUE(last.fit.ok);
  const DotPoseResult refit =
      refit_dot_pose(scene.span(), scene.camera, scene.base_from_camera, options(), last, last.fit.world_from_base);
  ASSERT_TRUE(refit.fit.ok);
  EXPECT_EQ(refit.markers_used, 3);
  EXPECT_TRUE(scene.markers[2].used);
}

TEST(DotPoseRefit, WithoutALastPoseSolvesInFull) {
  MarkerScene scene;
  const DotPoseResult refit = refit_dot_pose(scene.span(), scene.camera, scene.base_from_camera, options(),
                                             DotPoseResult{}, RigidTransform{});
  ASSERT_TRUE(refit.fit.ok);
  EXPECT_EQ(refit.markers_used, 3);
  EXPECT_LT((refit.fit.world_from_base.translation - scene.world_from_base.translation).norm(), 2e-4);
}

}  // namespace
}  // namespace irloc::dot
