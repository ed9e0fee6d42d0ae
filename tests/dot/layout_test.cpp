#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::dot {
namespace {

CellMask mask_of(std::initializer_list<std::pair<int, int>> cells) {
  CellMask mask = 0;
  for (const auto& [i, j] : cells) mask = static_cast<CellMask>(mask | (1u << cell_index(i, j)));
  return mask;
}

TEST(DotMarkerLayout, SpecTestVector1782) {
  const CellMask code = mask_of({{0, 1}, {0, 2}, {1, 0}, {1, 1}, {2, 2}, {2, 3}, {3, 1}, {3, 2}});
  EXPECT_EQ(1782, 0x6F6);
  EXPECT_EQ(id_from_cells(code | kDirectionCells), 1782);
  EXPECT_EQ(cells_from_id(1782), code | kDirectionCells);
}

TEST(DotMarkerLayout, EveryIdRoundTripsAndLeavesCell33Empty) {
  for (int id = 0; id <= kMaxMarkerId; ++id) {
    const CellMask cells = cells_from_id(id);
    ASSERT_EQ(id_from_cells(cells), id);
    ASSERT_EQ(cells & (1u << kCellNever), 0u);
    ASSERT_EQ(cells & kDirectionCells, kDirectionCells);
  }
}

TEST(DotMarkerLayout, WeightsAreTheSpecTable) {
  // The table of markers.md, row by row; O, X, Y and (3, 3) carry no weight.
  const int table[4][4] = {{0, 0x020, 0x200, 0}, {0x002, 0x010, 0x100, 0x800}, {0x001, 0x008, 0x080, 0x400},
                           {0, 0x004, 0x040, 0}};
  int sum = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_EQ(kCellWeights[static_cast<std::size_t>(cell_index(i, j))], table[i][j]) << i << "," << j;
      sum += table[i][j];
    }
  }
  EXPECT_EQ(sum, 4095);  // 12 distinct bits
}

TEST(DotMarkerLayout, CellsInTheWorldFollowTheMapConvention) {
  DotMarker marker;
  marker.origin = {1.0, 2.0, 2.6};
  marker.yaw = 0.7;
  marker.pitch = 0.05;
  const Eigen::Vector3d x_axis(std::cos(0.7), std::sin(0.7), 0), y_axis(std::sin(0.7), -std::cos(0.7), 0);
  EXPECT_TRUE(cell_in_world(marker, kCellO).isApprox(marker.origin));
  EXPECT_TRUE(cell_in_world(marker, kCellX).isApprox(marker.origin + 0.15 * x_axis));
  EXPECT_TRUE(cell_in_world(marker, kCellY).isApprox(marker.origin + 0.15 * y_axis));
  EXPECT_TRUE(cell_in_world(marker, cell_index(2, 1)).isApprox(marker.origin + 0.05 * x_axis + 0.10 * y_axis));
  // M's z = x cross y points down into the room.
  EXPECT_TRUE(x_axis.cross(y_axis).isApprox(Eigen::Vector3d(0, 0, -1)));
}

}  // namespace
}  // namespace irloc::dot
