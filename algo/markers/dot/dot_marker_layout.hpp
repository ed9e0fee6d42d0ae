#pragma once
// The dot-matrix ID marker of docs/markers.md: a 4 x 4 grid of cells, direction dots
// O (0,0), X (0,3), Y (3,0), cell (3,3) never populated, 12 weighted code cells.
//
// Cell (i, j): i along the marker's y axis, j along its x axis; its centre is (j p, i p, 0) in the
// marker frame M (p: the pitch). A cell index is 4 i + j.

#include <array>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "algo/map/marker_map.hpp"

namespace irloc::dot {

inline constexpr int kGridSize = 4;
inline constexpr int kCellCount = kGridSize * kGridSize;
inline constexpr int kCellO = 0;   // (0, 0)
inline constexpr int kCellX = 3;   // (0, 3)
inline constexpr int kCellY = 12;  // (3, 0)
inline constexpr int kCellNever = 15;  // (3, 3)
inline constexpr int kMaxMarkerId = 4095;

constexpr int cell_index(int i, int j) { return kGridSize * i + j; }
constexpr int cell_row(int cell) { return cell / kGridSize; }     // i
constexpr int cell_column(int cell) { return cell % kGridSize; }  // j

// The ID weight of each cell; 0 for O, X, Y and the never-populated cell.
inline constexpr std::array<std::uint16_t, kCellCount> kCellWeights = {
    0x000, 0x020, 0x200, 0x000,  //
    0x002, 0x010, 0x100, 0x800,  //
    0x001, 0x008, 0x080, 0x400,  //
    0x000, 0x004, 0x040, 0x000,
};

constexpr bool is_direction_cell(int cell) { return cell == kCellO || cell == kCellX || cell == kCellY; }
constexpr bool is_code_cell(int cell) { return kCellWeights[static_cast<std::size_t>(cell)] != 0; }

// A set of populated cells: bit k set = cell k holds a dot.
using CellMask = std::uint16_t;
inline constexpr CellMask kDirectionCells = (1u << kCellO) | (1u << kCellX) | (1u << kCellY);

// The ID of a cell set (the sum of the weights of its code cells).
constexpr int id_from_cells(CellMask cells) {
  int id = 0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    if ((cells >> cell) & 1u) id += kCellWeights[static_cast<std::size_t>(cell)];
  }
  return id;
}

// The populated cells of an ID: the direction dots plus its code dots. id in [0, 4095].
constexpr CellMask cells_from_id(int id) {
  CellMask cells = kDirectionCells;
  for (int cell = 0; cell < kCellCount; ++cell) {
    if (id & kCellWeights[static_cast<std::size_t>(cell)]) cells = static_cast<CellMask>(cells | (1u << cell));
  }
  return cells;
}

// Centre of a cell in the marker frame M, metres.
inline Eigen::Vector3d cell_in_marker(int cell, double pitch) {
  return {cell_column(cell) * pitch, cell_row(cell) * pitch, 0.0};
}

// Centre of a cell in the world frame W for a mapped ceiling marker: M's axes in W are
// x = (cos yaw, sin yaw, 0), y = (sin yaw, -cos yaw, 0), z = (0, 0, -1) (docs/formats.md).
Eigen::Vector3d cell_in_world(const DotMarker& marker, int cell);
// The same for any point of the grid: grid = (j, i) in pitches, cell (i, j)'s centre at (j, i).
Eigen::Vector3d grid_in_world(const DotMarker& marker, const Eigen::Vector2d& grid);

}  // namespace irloc::dot
