#include "algo/markers/square/tape_points.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace irloc {

TapePoints::TapePoints(const CeilingPlaneMap& plane, double cell, std::size_t capacity)
    : plane_(plane),
      cell_raw_(std::max<std::int64_t>(1, std::llround(cell * kPlaneRawPerMetre))),
      all_(capacity),
      votes_(capacity) {
  const std::int64_t radius_cells = static_cast<std::int64_t>(std::ceil(plane.max_radius() * kPlaneRawPerMetre / cell_raw_)) + 1;
  grid_origin_ = -radius_cells * cell_raw_;
  grid_size_ = static_cast<int>(2 * radius_cells);
  stamps_.assign(static_cast<std::size_t>(grid_size_) * static_cast<std::size_t>(grid_size_), 0);
}

TapePointCounters TapePoints::collect(const BitImage& mask, int x0, int y0) {
  TapePointCounters counters;
  all_count_ = 0;
  vote_count_ = 0;
  if (++stamp_ == 0) {  // the stamps wrapped: forget every old one, once in 65535 frames
    std::fill(stamps_.begin(), stamps_.end(), 0);
    stamp_ = 1;
  }
  for (int y = 0; y < mask.height(); ++y) {
    if (!mask.row_set(y)) continue;
    const std::uint64_t* words = mask.row(y);
    const PlanePoint* points = plane_.row(y0 + y) + x0;
    for (int w = 0; w < mask.words_per_row(); ++w) {
      for (std::uint64_t bits = words[w]; bits != 0; bits &= bits - 1) {
        const PlanePoint p = points[64 * w + std::countr_zero(bits)];
        if (p.x == CeilingPlaneMap::kNoPoint) continue;
        if (all_count_ == all_.size()) {
          ++counters.points_dropped;
          continue;
        }
        all_[all_count_++] = metres(p);
        const auto gx = static_cast<std::size_t>((p.x - grid_origin_) / cell_raw_);
        const auto gy = static_cast<std::size_t>((p.y - grid_origin_) / cell_raw_);
        std::uint16_t& stamp = stamps_[gy * static_cast<std::size_t>(grid_size_) + gx];
        if (stamp == stamp_) continue;
        stamp = stamp_;
        votes_[vote_count_++] = p;
      }
    }
  }
  counters.points = static_cast<std::uint32_t>(all_count_);
  counters.vote_points = static_cast<std::uint32_t>(vote_count_);
  return counters;
}

}  // namespace irloc
