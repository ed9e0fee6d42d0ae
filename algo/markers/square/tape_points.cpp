#include "algo/markers/square/tape_points.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "algo/source/rolling_shutter.hpp"

namespace irloc::square {

TapePoints::TapePoints(const CeilingPlaneMap& plane, double cell, std::size_t capacity, int patch_cells,
                       const Eigen::Vector2d& camera_xy)
    : plane_(plane),
      camera_xy_(camera_xy),
      cell_raw_(std::max<std::int64_t>(1, std::llround(cell * kPlaneRawPerMetre))),
      patch_cells_(patch_cells),
      all_(capacity),
      rows_(capacity),
      votes_(capacity),
      vote_cells_(capacity) {
  // A margin of half a window around the mapped disc: every window lies inside the grid.
  const std::int64_t radius_cells = static_cast<std::int64_t>(std::ceil(plane.max_radius() * kPlaneRawPerMetre / cell_raw_)) + 1 + kPatchWindow / 2;
  grid_origin_ = -radius_cells * cell_raw_;
  grid_size_ = static_cast<int>(2 * radius_cells);
  stamps_.assign(static_cast<std::size_t>(grid_size_) * static_cast<std::size_t>(grid_size_), 0);
  patches_.assign(stamps_.size(), 0);
}

TapePointCounters TapePoints::collect(const BitImage& mask, int x0, int y0, const RowMotion* rows) {
  TapePointCounters counters;
  all_count_ = 0;
  vote_count_ = 0;
  if (++stamp_ == 0) {  // the stamps wrapped: forget every old one, once in 65535 frames
    std::fill(stamps_.begin(), stamps_.end(), 0);
    std::fill(patches_.begin(), patches_.end(), 0);
    stamp_ = 1;
  }
  for (int y = 0; y < mask.height(); ++y) {
    if (mask.row_set(y)) collect_row(mask, y, x0, y0, rows, counters);
  }
  const std::size_t kept = drop_patches();
  counters.patch_cells = static_cast<std::uint32_t>(vote_count_ - kept);
  vote_count_ = kept;
  counters.points = static_cast<std::uint32_t>(all_count_);
  counters.vote_points = static_cast<std::uint32_t>(vote_count_);
  return counters;
}

void TapePoints::collect_row(const BitImage& mask, int y, int x0, int y0, const RowMotion* rows,
                             TapePointCounters& counters) {
  const std::uint64_t* words = mask.row(y);
  const PlanePoint* points = plane_.row(y0 + y) + x0;
  // The base frame at the row's time, in the base frame at t_ns: camera-centred plane point p
  // goes to turn (camera_xy + p) + travel - camera_xy = turn p + shift.
  Eigen::Matrix2d turn = Eigen::Matrix2d::Identity();
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  if (rows != nullptr) {
    const RigidTransform then = pose_after(RigidTransform{}, (y0 + y) * rows->line_time, rows->motion);
    turn = then.rotation.topLeftCorner<2, 2>();
    shift = then.translation.head<2>() + turn * camera_xy_ - camera_xy_;
  }
  for (int w = 0; w < mask.words_per_row(); ++w) {
    for (std::uint64_t bits = words[w]; bits != 0; bits &= bits - 1) {
      const PlanePoint p = points[64 * w + std::countr_zero(bits)];
      if (p.x == CeilingPlaneMap::kNoPoint) continue;
      if (all_count_ == all_.size()) {
        ++counters.points_dropped;
        continue;
      }
      rows_[all_count_] = y0 + y;
      all_[all_count_++] = rows != nullptr ? Eigen::Vector2d(turn * metres(p) + shift) : metres(p);
      const auto gx = static_cast<std::size_t>((p.x - grid_origin_) / cell_raw_);
      const auto gy = static_cast<std::size_t>((p.y - grid_origin_) / cell_raw_);
      const std::size_t index = gy * static_cast<std::size_t>(grid_size_) + gx;
      if (stamps_[index] == stamp_) continue;
      stamps_[index] = stamp_;
      vote_cells_[vote_count_] = static_cast<std::uint32_t>(index);
      votes_[vote_count_++] = p;
    }
  }
}

// Counted a window row at a time, up to the row where enough are found.
bool TapePoints::stamped_around(const std::vector<std::uint16_t>& grid, std::uint32_t cell, int enough) const {
  const auto row = static_cast<std::ptrdiff_t>(grid_size_);
  constexpr std::ptrdiff_t kHalf = kPatchWindow / 2;
  const std::uint16_t* const centre = grid.data() + cell;
  int count = 0;
  for (std::ptrdiff_t dy = -kHalf; dy <= kHalf; ++dy) {
    for (std::ptrdiff_t dx = -kHalf; dx <= kHalf; ++dx) count += centre[dy * row + dx] == stamp_;
    if (count >= enough) return true;
  }
  return false;
}

// The cells inside filled patches leave the vote (all cells are stamped by now), and so do those
// on a patch's rim, which alone would vote like a ring.
std::size_t TapePoints::drop_patches() {
  std::size_t outside = 0;
  for (std::size_t i = 0; i < vote_count_; ++i) {
    if (stamped_around(stamps_, vote_cells_[i], patch_cells_)) {
      patches_[vote_cells_[i]] = stamp_;
      continue;
    }
    votes_[outside] = votes_[i];
    vote_cells_[outside++] = vote_cells_[i];
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < outside; ++i) {
    if (!stamped_around(patches_, vote_cells_[i], kRimPatchCells)) votes_[kept++] = votes_[i];
  }
  return kept;
}

}  // namespace irloc::square
