// The geometric stages (grouping, direction dots, cell decoding) on candidate lists made from
// ideal projections of marker dots, with noise and stray blobs.

#include <random>

#include <gtest/gtest.h>

#include "algo/markers/dot/cell_decoder.hpp"
#include "algo/markers/dot/direction_dots.hpp"
#include "algo/markers/dot/dot_grouping.hpp"
#include "tests/dot/dot_scene.hpp"

namespace irloc::dot {
namespace {

using test::Scene;

struct Candidates {
  DotCandidateList list;
  std::vector<int> cell;  // the true cell of each candidate, -1 for strays
  std::vector<int> id;    // the true marker of each candidate, -1 for strays
};

// Candidates at the pinhole projections of every dot of the scene's markers plus strays (world
// points), with Gaussian pixel noise.
Candidates make_candidates(const Scene& scene, const std::vector<DotMarker>& markers,
                           const std::vector<Eigen::Vector3d>& strays, double noise_px, unsigned seed = 3) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_px);
  const Eigen::Vector3d up_c = scene.camera_from_world().linear() * Eigen::Vector3d::UnitZ();
  const NominalPlane plane(up_c, 2.3);
  Candidates out;
  const auto add = [&](const Eigen::Vector3d& world, int cell, int id) {
    Eigen::Vector2d pixel;
    if (!scene.project(world, pixel)) return;
    pixel += Eigen::Vector2d(noise(random), noise(random));
    DotCandidate c;
    c.pixel = pixel;
    c.bearing = Eigen::Vector3d((pixel.x() - scene.camera.cx) / scene.camera.fx,
                                (pixel.y() - scene.camera.cy) / scene.camera.fy, 1.0)
                    .normalized();
    ASSERT_TRUE(plane.intersect(c.bearing, c.plane));
    c.mean_intensity = 150;
    c.area = 15;
    out.list.push_back(c);
    out.cell.push_back(cell);
    out.id.push_back(id);
  };
  for (const DotMarker& marker : markers) {
    const CellMask cells = cells_from_id(marker.id);
    for (int cell = 0; cell < kCellCount; ++cell) {
      if ((cells >> cell) & 1u) add(cell_in_world(marker, cell), cell, marker.id);
    }
  }
  for (const Eigen::Vector3d& stray : strays) add(stray, -1, -1);
  return out;
}

constexpr double kPitch = 0.04;
const double kDiagonal = 3 * std::sqrt(2.0) * kPitch;

TEST(DotGrouping, SeparatesMarkersAndLeavesFarStraysOut) {
  Scene scene;
  scene.world_from_base = test::level_pose(1.0, 1.0, 0.2);
  const std::vector<DotMarker> markers = {test::ceiling_marker(1782, 1.0, 1.0, 0.0),
                                          test::ceiling_marker(5, 1.5, 1.2, 1.0),
                                          test::ceiling_marker(4095 - 0x800, 0.6, 0.7, -2.0)};
  const std::vector<Eigen::Vector3d> strays = {{1.3, 0.5, 2.6}, {0.4, 1.4, 2.6}, {1.6, 0.7, 2.6}};
  const Candidates c = make_candidates(scene, markers, strays, 0.1);
  DotGroupList groups;
  const GroupingCounters counters = group_candidates(c.list, 1.3 * 3 * kPitch, groups);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(counters.too_small, 3u);  // each stray alone
  for (const DotGroup& group : groups) {
    const int id = c.id[group.members[0]];
    EXPECT_GE(id, 0);
    for (const std::uint8_t member : group.members) EXPECT_EQ(c.id[member], id);
    EXPECT_EQ(static_cast<int>(group.members.size()), std::popcount(cells_from_id(id)));
  }
}

class DirectionDotsAtYaw : public ::testing::TestWithParam<double> {};

TEST_P(DirectionDotsAtYaw, FindsOXYAndDecodes1782) {
  Scene scene;
  scene.world_from_base = test::level_pose(1.02, 0.97, 0.3);
  const DotMarker marker = test::ceiling_marker(1782, 1.0, 1.0, GetParam());
  // A stray 5 cm beyond X, inside the link distance: it must be dropped, not taken for X.
  const Eigen::Vector3d beyond_x = cell_in_world(marker, kCellX) +
                                   0.05 * Eigen::Vector3d(std::cos(GetParam()), std::sin(GetParam()), 0);
  const Candidates c = make_candidates(scene, {marker}, {beyond_x}, 0.15);
  DotGroupList groups;
  group_candidates(c.list, 1.3 * 3 * kPitch, groups);
  ASSERT_EQ(groups.size(), 1u);
  DotGroup group = groups[0];
  DotSourceConfig config;
  DirectionDots found;
  ASSERT_TRUE(find_direction_dots(c.list, config, kDiagonal, group, found));
  EXPECT_EQ(group.members.size(), groups[0].members.size() - 1);
  for (const std::uint8_t member : group.members) EXPECT_NE(c.cell[member], -1) << "the stray is still a member";
  EXPECT_EQ(c.cell[found.o], kCellO);
  EXPECT_EQ(c.cell[found.x], kCellX);
  EXPECT_EQ(c.cell[found.y], kCellY);
  EXPECT_LT(found.right_angle_error, 0.05);

  DecodedCells decoded;
  ASSERT_TRUE(decode_cells(c.list, group, found, config.snap_tolerance, decoded));
  EXPECT_EQ(decoded.id, 1782);
  for (int cell = 0; cell < kCellCount; ++cell) {
    const std::int16_t index = decoded.candidate_of_cell[static_cast<std::size_t>(cell)];
    if (index >= 0) {
      EXPECT_EQ(c.cell[static_cast<std::size_t>(index)], cell);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Yaws, DirectionDotsAtYaw, ::testing::Values(0.0, 0.8, 1.5708, 2.9, -2.2, -0.4));

TEST(DirectionDots, AMirroredMarkerSwapsXAndY) {
  // The same dots seen from above (a mirror image) must not be read as the original marker: the
  // cross product assigns X and Y the other way round.
  Scene scene;
  const DotMarker marker = test::ceiling_marker(0, 0.0, 0.0, 0.4);
  Candidates c = make_candidates(scene, {marker}, {}, 0.0);
  for (DotCandidate& candidate : c.list) candidate.plane.y() = -candidate.plane.y();
  DotGroupList groups;
  group_candidates(c.list, 1.3 * 3 * kPitch, groups);
  ASSERT_EQ(groups.size(), 1u);
  DirectionDots found;
  ASSERT_TRUE(find_direction_dots(c.list, DotSourceConfig{}, kDiagonal, groups[0], found));
  EXPECT_EQ(c.cell[found.x], kCellY);
  EXPECT_EQ(c.cell[found.y], kCellX);
}

TEST(DirectionDots, RejectsAWrongTriangleAndLeavesTheGroupWhole) {
  // Three dots in a row and a skewed triangle are not O, X, Y. The members set aside as strays
  // on the way stay in the group: the track may still identify it whole.
  DotCandidateList list;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0, 0), Eigen::Vector2d(0.08, 0.0), Eigen::Vector2d(0.17, 0.0)}) {
    DotCandidate c;
    c.plane = p;
    list.push_back(c);
  }
  DotGroup group;
  for (std::uint8_t k = 0; k < 3; ++k) group.members.push_back(k);
  DirectionDots found;
  EXPECT_FALSE(find_direction_dots(list, DotSourceConfig{}, kDiagonal, group, found));
  EXPECT_EQ(group.members.size(), 3u);
  list[2].plane = {0.15, 0.09};
  DotGroup skewed;
  for (std::uint8_t k = 0; k < 3; ++k) skewed.members.push_back(k);
  EXPECT_FALSE(find_direction_dots(list, DotSourceConfig{}, kDiagonal, skewed, found));
  EXPECT_EQ(skewed.members.size(), 3u);
}

TEST(CellDecoder, SurvivesATiltedView) {
  // A 12 degree roll: the grid is seen in perspective, the decoding uses the homography.
  Scene scene;
  scene.world_from_base = Eigen::Isometry3d::Identity();
  scene.world_from_base.linear() = rotation_from_rpy(0.21, -0.1, 0.5);
  const DotMarker marker = test::ceiling_marker(0xABC, 0.5, 0.2, 2.0);
  const Candidates c = make_candidates(scene, {marker}, {}, 0.1);
  DotGroupList groups;
  group_candidates(c.list, 1.3 * 3 * kPitch, groups);
  ASSERT_EQ(groups.size(), 1u);
  DirectionDots found;
  ASSERT_TRUE(find_direction_dots(c.list, DotSourceConfig{}, kDiagonal, groups[0], found));
  DecodedCells decoded;
  ASSERT_TRUE(decode_cells(c.list, groups[0], found, 0.3, decoded));
  EXPECT_EQ(decoded.id, 0xABC);
  EXPECT_EQ(decoded.strays, 0);
}

TEST(CellDecoder, ADotInCell33IsNotAMarker) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(0x0F0, 0.0, 0.0, 0.0);
  const Candidates c = make_candidates(scene, {marker}, {cell_in_world(marker, kCellNever)}, 0.0);
  DotGroupList groups;
  group_candidates(c.list, 1.3 * 3 * kPitch, groups);
  ASSERT_EQ(groups.size(), 1u);
  // With (3, 3) populated, O-(3,3) ties with X-Y as the farthest pair and either of O and (3,3)
  // can pass for O; either way a dot lands in the never-populated cell and no ID comes out.
  DirectionDots found;
  if (find_direction_dots(c.list, DotSourceConfig{}, kDiagonal, groups[0], found)) {
    DecodedCells decoded;
    EXPECT_FALSE(decode_cells(c.list, groups[0], found, 0.3, decoded));
    EXPECT_EQ(decoded.id, -1);
  }
}

}  // namespace
}  // namespace irloc::dot
