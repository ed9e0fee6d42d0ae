#pragma once
// Connected components (8-connectivity) over horizontal runs, straight to per-blob statistics.
//
// The run extractors (BlobLabeller, FusedFrontEnd) feed runs row by row, each with its
// intensity sums (run_sums, formed while the run's row is at hand); each run is linked to the runs
// of the row above that touch it, including diagonally, in a union-find whose root is always the
// component's first run in raster order, and its sums are added to its component's at once (two
// components that a run joins are combined then). collect() only lists the components: no pass
// over the runs' pixels after the scan. Work is bounded by max_runs (fixed at start-up): runs
// beyond it are counted and left out of every blob.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/kernels/pixel_run.hpp"

namespace irloc {

// What a frame's labelling saw; every "dropped" count is an overflow report.
struct BlobCounters {
  std::uint32_t foreground_pixels = 0;  // pixels above threshold (or nonzero in a mask)
  std::uint32_t runs = 0;               // runs stored
  std::uint32_t runs_dropped = 0;       // runs beyond max_runs; their pixels are in no blob
  std::uint32_t components = 0;         // 8-connected components among the stored runs
  std::uint32_t blobs_too_small = 0;    // components below min_area, not reported
  std::uint32_t blobs_dropped = 0;      // components that did not fit in the BlobList
};

struct BlobParams {
  std::uint32_t min_area = 1;  // smaller components are counted, not reported
};

// The intensity sums of one run: over its pixels x, sum of I, I x, I x^2, and the largest I.
struct RunSums {
  std::uint64_t sum_i = 0;
  std::uint64_t sum_ix = 0;
  std::uint64_t sum_ixx = 0;
  std::uint32_t peak = 0;
};

// The sums of the run [x_begin, x_end), intensity(x) giving each pixel's I >= 1.
template <typename Intensity>
RunSums run_sums(int x_begin, int x_end, const Intensity& intensity) {
  RunSums sums;
  for (int x = x_begin; x < x_end; ++x) {
    const std::uint64_t value = intensity(x);
    const std::uint64_t value_x = value * static_cast<std::uint64_t>(x);
    sums.sum_i += value;
    sums.sum_ix += value_x;
    sums.sum_ixx += value_x * static_cast<std::uint64_t>(x);
    sums.peak = std::max(sums.peak, static_cast<std::uint32_t>(value));
  }
  return sums;
}

class RunLabeller {
 public:
  // The only allocations: the run table, its union-find and the components' sums, max_runs
  // entries each.
  explicit RunLabeller(std::size_t max_runs);

  void begin_frame();

  // The run of foreground pixels [x_begin, x_end) in row y, with its intensity sums. Rows arrive
  // in increasing y, runs of a row in increasing x and not touching each other. A run beyond a
  // full table is counted as dropped.
  void add_run(int y, int x_begin, int x_end, const RunSums& sums) {
    if (count_ == runs_.size()) {
      ++runs_dropped_;
      return;
    }
    if (y != row_y_) start_row(y);
    const auto index = static_cast<std::uint32_t>(count_++);
    runs_[index] = {y, x_begin, x_end};
    // Runs of the row above touch this one (8-connectivity) when they end at or after x_begin - 1
    // and start at or before x_end (exclusive ends). Earlier runs of this row need none of the
    // ones that end before x_begin, so the cursor only moves forward.
    while (above_cursor_ < above_end_ && runs_[above_cursor_].x_end < x_begin) ++above_cursor_;
    std::uint32_t root = index;  // every other root is an earlier run
    for (std::size_t k = above_cursor_; k < above_end_ && runs_[k].x_begin <= x_end; ++k) {
      const std::uint32_t other = find(static_cast<std::uint32_t>(k));
      if (root == index) root = other;
      else if (other != root) root = combine(root, other);
    }
    parent_[index] = root;
    if (root == index) open_component(index);
    add_to_component(runs_[index], sums, components_[component_of_root_[root]]);
  }

  // Lists the components in raster order of their first pixel: those of at least min_area pixels
  // as Blobs, as many as fit.
  void collect(BlobParams params, BlobList& blobs, BlobCounters& counters);

  // The runs stored since begin_frame(), in raster order (those beyond max_runs are dropped and
  // counted in collect()'s counters).
  std::span<const PixelRun> runs() const { return {runs_.data(), count_}; }

  // labels(x, y) = 1 + index of the pixel's blob in the last collect()'s list, 0 for background
  // and for pixels of unreported components. For tests and debugging; labels has the frame's size.
  void paint_labels(ImageView<std::int32_t> labels) const;

 private:
  static constexpr std::int32_t kNoBlob = -1;

  // A component whose first run is run, with no pixel summed yet.
  void open_component(std::uint32_t run);
  // Links the later of two roots under the earlier and adds its sums to the earlier's; returns
  // the earlier.
  std::uint32_t combine(std::uint32_t root_a, std::uint32_t root_b);
  static void add_to_component(const PixelRun& run, const RunSums& sums, Blob& component);

  void start_row(int y) {
    // The row just finished is "above" only if it is the row directly above y.
    above_begin_ = y == row_y_ + 1 ? row_begin_ : count_;
    above_end_ = count_;
    above_cursor_ = above_begin_;
    row_begin_ = count_;
    row_y_ = y;
  }
  std::uint32_t find(std::uint32_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // path halving
      i = parent_[i];
    }
    return i;
  }

  std::vector<PixelRun> runs_;
  std::vector<std::uint32_t> parent_;
  // Per root run: its component's entry in components_ while runs arrive; after collect(), its
  // blob index or kNoBlob.
  std::vector<std::int32_t> component_of_root_;
  std::vector<Blob> components_;  // the sums of each component opened this frame, in opening order
  std::size_t count_ = 0;
  std::size_t component_count_ = 0;
  std::uint32_t runs_dropped_ = 0;
  int row_y_ = -2;
  std::size_t row_begin_ = 0;
  std::size_t above_begin_ = 0;
  std::size_t above_end_ = 0;
  std::size_t above_cursor_ = 0;
};

inline void RunLabeller::add_to_component(const PixelRun& run, const RunSums& sums, Blob& component) {
  const auto length = static_cast<std::uint64_t>(run.x_end - run.x_begin);
  const auto y = static_cast<std::uint64_t>(run.y);
  component.area += static_cast<std::uint32_t>(length);
  component.x_min = std::min(component.x_min, run.x_begin);
  component.x_max = std::max(component.x_max, run.x_end - 1);
  component.y_max = run.y;  // runs arrive in raster order
  component.sum_x += static_cast<std::uint64_t>(run.x_begin + run.x_end - 1) * length / 2;
  component.sum_y += y * length;
  component.peak = std::max(component.peak, sums.peak);
  component.sum_i += sums.sum_i;
  component.sum_ix += sums.sum_ix;
  component.sum_iy += sums.sum_i * y;
  component.sum_ixx += sums.sum_ixx;
  component.sum_iyy += sums.sum_i * y * y;
  component.sum_ixy += sums.sum_ix * y;
}

}  // namespace irloc
