#pragma once
// Stage 4a: a group's dots assigned to grid cells in the marker plane, and the ID they spell.
//
// The grid (cell (i, j) at (j, i) in pitch units) is first mapped onto the nominal ceiling plane
// by the affine map fixed by O, X and Y; every dot within snap_tolerance pitches of a cell centre
// is assigned to it; with four or more assigned dots the map is refined to a homography (exact
// for a plane seen through a central camera, so tilt and wide-angle lenses do not matter) and the
// dots are assigned again. Dots near no cell are strays and spell nothing.

#include <array>
#include <cstdint>

#include <Eigen/Core>

#include "algo/markers/dot/direction_dots.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"

namespace irloc::dot {

struct DecodedCells {
  CellMask cells = 0;                     // populated cells
  int id = -1;                            // id_from_cells(cells), or -1 when the layout is impossible
  std::array<std::int16_t, kCellCount> candidate_of_cell{};  // candidate index per cell, -1 when empty
  Eigen::Matrix3d grid_to_plane = Eigen::Matrix3d::Identity();  // grid (pitch units) -> nominal plane
  double max_snap_error = 0;              // largest dot-to-cell distance, pitches
  int strays = 0;                         // group dots on no cell
};

// false when the layout cannot be a marker (a dot in the never-populated cell (3, 3), or O, X, Y
// not on their own cells after refinement).
bool decode_cells(const DotCandidateList& candidates, const DotGroup& group, const DirectionDots& direction,
                  double snap_tolerance, DecodedCells& decoded);

}  // namespace irloc::dot
