#pragma once
// The tape pixels of a mask, mapped to the ceiling plane: all of them, in metres (double, for the
// least-squares refinement of each side and the dash patterns), and a thinned set with at most one
// point per cell of a plane grid, as PlanePoint (Q23.8 cm, for the fixed-point Hough vote), so
// that near tape, seen by many pixels, does not outvote far tape and the vote costs the same
// wherever the square is. A cell inside a filled patch of cells (at least patch_cells of the 5 x 5
// cells around it occupied) does not vote: tape two cells wide never fills that many, while the
// speckle of LED-lit skin or cloth close to the camera, the inside of a wide strip and a crescent
// do, and would vote in every direction. Nor does a cell on the rim of a broad patch (at least
// kRimPatchCells patch cells in its window), which alone would vote like a ring; a strip's patch
// cells are a line one or two cells wide, and a side beside it keeps its votes.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "algo/kernels/bit_image.hpp"
#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/source/source_input.hpp"

namespace irloc::square {

struct TapePointCounters {
  std::uint32_t points = 0;          // mask pixels on the mapped ceiling
  std::uint32_t points_dropped = 0;  // beyond the capacity
  std::uint32_t vote_points = 0;     // one per occupied grid cell outside filled patches
  std::uint32_t patch_cells = 0;     // occupied cells in filled patches or on their rims (no vote)
};

// Under a rolling shutter, row y of a frame is seen y * line_time after the frame's t_ns by a
// robot moving as `motion` within the frame (algo/source/rolling_shutter.hpp).
struct RowMotion {
  FrameMotion motion;
  double line_time = 0;  // seconds a row
};

class TapePoints {
 public:
  // cell: the grid's cell size in metres; capacity: most points kept per frame; patch_cells: see
  // above (26 or more: no cell is left out); camera_xy: the camera centre in the base frame (the
  // plane's origin), metres.
  TapePoints(const CeilingPlaneMap& plane, double cell, std::size_t capacity, int patch_cells,
             const Eigen::Vector2d& camera_xy);

  static constexpr int kPatchWindow = 5;  // cells a side, centred on the cell
  // patch_cells for cells w/2 wide, w the tape's width: straight tape up to 1.3 w wide (blurred)
  // fills at most 21 of a window at any angle (19 for w itself, at 45 degrees); a corner's two arms
  // may fill 22 and lose a cell or two.
  static constexpr int kTapePatchCells = 22;
  static constexpr int kRimPatchCells = 6;

  // mask: a region of the plane map's pixels whose top-left pixel is (x0, y0); its set pixels are
  // collected in raster order. With rows, all() holds each point where the level robot at the
  // frame's t_ns would have mapped it: seen from the base frame at its row's time, carried into
  // the base frame at t_ns (a turn about z and a move in the plane; the plane's scale taken as
  // the table's, which a dof 4 height change alters by a few percent of a correction of
  // millimetres). The vote points stay as seen: the Hough search is coarse. Allocates nothing.
  TapePointCounters collect(const BitImage& mask, int x0, int y0, const RowMotion* rows = nullptr);

  std::span<const Eigen::Vector2d> all() const { return {all_.data(), all_count_}; }
  // The image row each point of all() was seen in.
  std::span<const int> rows() const { return {rows_.data(), all_count_}; }
  std::span<const PlanePoint> vote_points() const { return {votes_.data(), vote_count_}; }

 private:
  // Row y of the mask's points into all() and, one per grid cell, the vote.
  void collect_row(const BitImage& mask, int y, int x0, int y0, const RowMotion* rows, TapePointCounters& counters);
  // Whether at least `enough` cells of grid in the kPatchWindow square around cell were stamped
  // this frame.
  bool stamped_around(const std::vector<std::uint16_t>& grid, std::uint32_t cell, int enough) const;
  // The vote without the patches' cells and their rims; returns the votes kept (in front).
  std::size_t drop_patches();

  const CeilingPlaneMap& plane_;
  Eigen::Vector2d camera_xy_;
  std::int64_t cell_raw_;     // Q23.8 plane units per cell
  std::int64_t grid_origin_;  // Q23.8: -(max radius), rounded out to a cell
  int grid_size_;             // cells per side
  int patch_cells_;
  std::vector<Eigen::Vector2d> all_;  // metres
  std::vector<int> rows_;             // image rows
  std::vector<PlanePoint> votes_;
  std::vector<std::uint32_t> vote_cells_;  // the grid index of each vote point's cell
  std::size_t all_count_ = 0;
  std::size_t vote_count_ = 0;
  // Cell occupancy stamped with the frame number, so that no frame has to clear the grid.
  std::vector<std::uint16_t> stamps_;
  std::vector<std::uint16_t> patches_;  // the cells found inside filled patches, stamped alike
  std::uint16_t stamp_ = 0;
};

}  // namespace irloc::square
