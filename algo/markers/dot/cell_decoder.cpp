#include "algo/markers/dot/cell_decoder.hpp"

#include <cmath>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/homography.hpp"

namespace irloc::dot {
namespace {

Eigen::Vector2d cell_in_grid(int cell) { return {cell_column(cell), cell_row(cell)}; }

// Assigns each group dot to the nearest cell through plane_to_grid; keeps the closest dot per cell.
void assign(const DotCandidateList& candidates, const DotGroup& group, const Eigen::Matrix3d& plane_to_grid,
            double snap_tolerance, DecodedCells& decoded) {
  std::array<double, kCellCount> best{};
  best.fill(snap_tolerance);
  decoded.candidate_of_cell.fill(-1);
  decoded.strays = 0;
  decoded.max_snap_error = 0;
  for (const std::uint8_t member : group.members) {
    const Eigen::Vector2d grid = apply_homography(plane_to_grid, candidates[member].plane);
    const long j = std::lround(grid.x());
    const long i = std::lround(grid.y());
    if (i < 0 || i >= kGridSize || j < 0 || j >= kGridSize) {
      ++decoded.strays;
      continue;
    }
    const int cell = cell_index(static_cast<int>(i), static_cast<int>(j));
    const double error = (grid - cell_in_grid(cell)).norm();
    if (error >= snap_tolerance) {
      ++decoded.strays;
      continue;
    }
    if (error < best[static_cast<std::size_t>(cell)]) {
      if (decoded.candidate_of_cell[static_cast<std::size_t>(cell)] >= 0) ++decoded.strays;  // the one replaced
      best[static_cast<std::size_t>(cell)] = error;
      decoded.candidate_of_cell[static_cast<std::size_t>(cell)] = static_cast<std::int16_t>(member);
    } else {
      ++decoded.strays;
    }
  }
  decoded.cells = 0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    if (decoded.candidate_of_cell[static_cast<std::size_t>(cell)] < 0) continue;
    decoded.cells = static_cast<CellMask>(decoded.cells | (1u << cell));
    decoded.max_snap_error = std::max(decoded.max_snap_error, best[static_cast<std::size_t>(cell)]);
  }
}

}  // namespace

bool decode_cells(const DotCandidateList& candidates, const DotGroup& group, const DirectionDots& direction,
                  double snap_tolerance, DecodedCells& decoded) {
  // Affine grid -> plane from the direction dots: O at (0, 0), X at (3, 0), Y at (0, 3).
  const Eigen::Vector2d o = candidates[direction.o].plane;
  const Eigen::Vector2d step_x = (candidates[direction.x].plane - o) / 3.0;
  const Eigen::Vector2d step_y = (candidates[direction.y].plane - o) / 3.0;
  Eigen::Matrix3d grid_to_plane;
  grid_to_plane << step_x.x(), step_y.x(), o.x(), step_x.y(), step_y.y(), o.y(), 0, 0, 1;
  assign(candidates, group, grid_to_plane.inverse(), snap_tolerance, decoded);

  // Refine to a homography with every assigned dot.
  StaticVector<Eigen::Vector2d, kCellCount> grid_points, plane_points;
  for (int cell = 0; cell < kCellCount; ++cell) {
    const std::int16_t member = decoded.candidate_of_cell[static_cast<std::size_t>(cell)];
    if (member < 0) continue;
    grid_points.push_back(cell_in_grid(cell));
    plane_points.push_back(candidates[static_cast<std::size_t>(member)].plane);
  }
  Eigen::Matrix3d refined;
  if (grid_points.size() >= 5 &&
      fit_homography({grid_points.begin(), grid_points.size()}, {plane_points.begin(), plane_points.size()}, refined)) {
    grid_to_plane = refined;
    assign(candidates, group, grid_to_plane.inverse(), snap_tolerance, decoded);
  }
  decoded.grid_to_plane = grid_to_plane;

  const bool directions_kept = decoded.candidate_of_cell[kCellO] == direction.o &&
                               decoded.candidate_of_cell[kCellX] == direction.x &&
                               decoded.candidate_of_cell[kCellY] == direction.y;
  const bool possible = directions_kept && (decoded.cells & (1u << kCellNever)) == 0;
  decoded.id = possible ? id_from_cells(decoded.cells) : -1;
  return possible;
}

}  // namespace irloc::dot
