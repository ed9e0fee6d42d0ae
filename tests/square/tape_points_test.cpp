// TapePoints: every mapped mask pixel is a point, and one vote point per occupied plane cell but
// those inside a filled patch or on its rim: tape at any angle keeps all its cells, a filled disc
// (the speckle of LED-lit skin close to the camera, the inside of a crescent) at most a few cells
// of its edge.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "algo/geometry/camera_model.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/tape_points.hpp"
#include "tests/square/tape_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

constexpr int kSize = 400;
constexpr double kCell = 0.025;  // w / 2 for tape w = 5 cm
constexpr int kNoPatch = 26;     // more than a window holds: every cell votes

// A pinhole camera 2 m below the ceiling, looking up: a pixel is 5 mm on the plane, everywhere
// (tape close to the camera: every cell its band touches gets points).
CameraIntrinsics pinhole_up() {
  CameraIntrinsics intrinsics;
  intrinsics.width = kSize;
  intrinsics.height = kSize;
  intrinsics.fx = intrinsics.fy = 400;
  intrinsics.cx = intrinsics.cy = (kSize - 1) / 2.0;
  return intrinsics;
}

// Pixels within half_width of the segment from a to b (pixels).
BitImage tape(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double half_width) {
  BitImage mask(kSize, kSize);
  const Eigen::Vector2d along = (b - a).normalized();
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const Eigen::Vector2d d = Eigen::Vector2d(x, y) - a;
      const double s = d.dot(along);
      if (s >= 0 && s <= (b - a).norm() && std::abs(d.x() * along.y() - d.y() * along.x()) <= half_width) {
        mask.set_range(y, x, x + 1);
      }
    }
  }
  return mask;
}

BitImage disc(const Eigen::Vector2d& centre, double radius) {
  BitImage mask(kSize, kSize);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      if ((Eigen::Vector2d(x, y) - centre).norm() <= radius) mask.set_range(y, x, x + 1);
    }
  }
  return mask;
}

// The plane of pinhole_up(), and tape points from it with and without the patch rule.
class TapePointsTest : public testing::Test {
 protected:
  const CameraModel camera{pinhole_up()};
  const CeilingPlaneMap plane{camera, to_rigid(up_mount()), 2.0, 1.0};
  TapePoints every_cell{plane, kCell, kSize * kSize, kNoPatch, Eigen::Vector2d::Zero()};
  TapePoints tape_points{plane, kCell, kSize * kSize, TapePoints::kTapePatchCells, Eigen::Vector2d::Zero()};
};

TEST_F(TapePointsTest, TapeAtAnyAngleKeepsEveryCell) {
  const Eigen::Vector2d centre(200, 200);
  for (const double degrees : {0.0, 10.0, 22.5, 30.0, 45.0, 60.0, 80.0, 90.0, 135.0}) {
    SCOPED_TRACE(testing::Message() << degrees << " degrees");
    const double angle = degrees * std::numbers::pi / 180;
    const Eigen::Vector2d half(160 * std::cos(angle), 160 * std::sin(angle));
    const BitImage mask = tape(centre - half, centre + half, 5);  // 5 cm wide, 1.6 m long
    const TapePointCounters reference = every_cell.collect(mask, 0, 0);
    AllocationCounter allocations;
    const TapePointCounters counted = tape_points.collect(mask, 0, 0);
    EXPECT_EQ(allocations.count(), 0u);
    EXPECT_EQ(counted.points, reference.points);
    EXPECT_EQ(counted.patch_cells, 0u);
    EXPECT_EQ(counted.vote_points, reference.vote_points);
    EXPECT_GE(counted.vote_points, 2 * 160 / 2.5);  // at least two cells across along its length
  }
}

TEST_F(TapePointsTest, AFilledPatchDoesNotVote) {
  const Eigen::Vector2d centre(230, 170);
  const double radius = 80;  // px: 40 cm
  const BitImage mask = disc(centre, radius);
  const TapePointCounters reference = every_cell.collect(mask, 0, 0);
  const TapePointCounters counted = tape_points.collect(mask, 0, 0);
  EXPECT_EQ(counted.points, reference.points);
  EXPECT_EQ(counted.vote_points + counted.patch_cells, reference.vote_points);
  EXPECT_GT(counted.patch_cells, 9 * reference.vote_points / 10);
  // What still votes lies within three cells of the disc's edge.
  const PlanePoint raw_centre = plane.row(static_cast<int>(centre.y()))[static_cast<int>(centre.x())];
  const Eigen::Vector2d disc_centre(raw_centre.x / kPlaneRawPerMetre, raw_centre.y / kPlaneRawPerMetre);
  ASSERT_EQ(tape_points.vote_points().size(), counted.vote_points);
  for (const PlanePoint& p : tape_points.vote_points()) {
    const double from_centre = (Eigen::Vector2d(p.x / kPlaneRawPerMetre, p.y / kPlaneRawPerMetre) - disc_centre).norm();
    EXPECT_GE(from_centre, radius / 200 - 3 * kCell);
  }
}

}  // namespace
}  // namespace irloc::test
