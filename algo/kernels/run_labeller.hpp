#pragma once
// Connected components (8-connectivity) over horizontal runs, straight to per-blob statistics.
//
// The run extractors (BlobLabeller, FusedFrontEnd) feed runs row by row; each run is linked to the
// runs of the row above that touch it, including diagonally, in a union-find whose root is always
// the component's first run in raster order. collect() then sums every run into its component's
// Blob, reading the run's intensities through an accessor (the fused front end's are kept from its
// flag rows, the mask labeller's are an image's). Work is bounded by max_runs (fixed
// at start-up): runs beyond it are counted and left out of every blob.

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

class RunLabeller {
 public:
  // The only allocations: the run table and its union-find, max_runs entries each.
  explicit RunLabeller(std::size_t max_runs);

  void begin_frame();

  // The run of foreground pixels [x_begin, x_end) in row y. Rows arrive in increasing y, runs of a
  // row in increasing x and not touching each other. false: the run table is full, and the run is
  // counted as dropped.
  bool add_run(int y, int x_begin, int x_end) {
    if (count_ == runs_.size()) {
      ++runs_dropped_;
      return false;
    }
    if (y != row_y_) start_row(y);
    const auto index = static_cast<std::uint32_t>(count_++);
    runs_[index] = {y, x_begin, x_end};
    parent_[index] = index;
    // Runs of the row above touch this one (8-connectivity) when they end at or after x_begin - 1
    // and start at or before x_end (exclusive ends). Earlier runs of this row need none of the
    // ones that end before x_begin, so the cursor only moves forward.
    while (above_cursor_ < above_end_ && runs_[above_cursor_].x_end < x_begin) ++above_cursor_;
    for (std::size_t k = above_cursor_; k < above_end_ && runs_[k].x_begin <= x_end; ++k) {
      unite(static_cast<std::uint32_t>(k), index);
    }
    return true;
  }

  // Sums every stored run into the Blob of its component. intensity(run, pixels_before) returns
  // the accessor of the run's pixels, whose (x) gives a pixel's I >= 1 for x in [run.x_begin,
  // run.x_end); pixels_before is the number of pixels in the stored runs before it (where a run
  // extractor that kept the runs' values in raster order finds them). Blobs come in raster order of
  // their first pixel.
  template <typename Intensity>
  void collect(const Intensity& intensity, BlobParams params, BlobList& blobs, BlobCounters& counters);

  // The runs stored since begin_frame(), in raster order (those beyond max_runs are dropped and
  // counted in collect()'s counters).
  std::span<const PixelRun> runs() const { return {runs_.data(), count_}; }

  // labels(x, y) = 1 + index of the pixel's blob in the last collect()'s list, 0 for background
  // and for pixels of unreported components. For tests and debugging; labels has the frame's size.
  void paint_labels(ImageView<std::int32_t> labels) const;

 private:
  static constexpr std::int32_t kNoBlob = -1;

  // The blob slot of the component whose first run (root) is run, blob_of_run_[run] holding its
  // area: a new Blob seeded with the run's box, or kNoBlob when the component is below min_area
  // or the list is full (both counted).
  std::int32_t open_blob(std::size_t run, std::uint32_t min_area, BlobList& blobs, BlobCounters& counters);
  // Adds the run's pixels, row(x) giving each one's I, to the blob's sums.
  template <typename RunIntensity>
  static void add_run_to_blob(const PixelRun& run, const RunIntensity& row, Blob& blob);

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
  // Links the later root under the earlier one, so a root is its component's first run.
  void unite(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t root_a = find(a);
    const std::uint32_t root_b = find(b);
    if (root_a < root_b) parent_[root_b] = root_a;
    else parent_[root_a] = root_b;
  }

  std::vector<PixelRun> runs_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::int32_t> blob_of_run_;  // per run: blob index or kNoBlob (a root's area first)
  std::size_t count_ = 0;
  std::uint32_t runs_dropped_ = 0;
  int row_y_ = -2;
  std::size_t row_begin_ = 0;
  std::size_t above_begin_ = 0;
  std::size_t above_end_ = 0;
  std::size_t above_cursor_ = 0;
};

template <typename Intensity>
void RunLabeller::collect(const Intensity& intensity, BlobParams params, BlobList& blobs, BlobCounters& counters) {
  blobs.clear();
  counters.runs = static_cast<std::uint32_t>(count_);
  counters.runs_dropped = runs_dropped_;
  counters.components = 0;
  counters.blobs_too_small = 0;
  // Flatten, and sum the areas on the roots: in index order every parent is an earlier, already
  // flattened run, so one hop reaches the root, and a root comes before its component's other runs.
  for (std::size_t i = 0; i < count_; ++i) {
    const std::uint32_t root = parent_[parent_[i]];
    parent_[i] = root;
    const std::int32_t length = runs_[i].x_end - runs_[i].x_begin;
    if (root == i) blob_of_run_[i] = length;
    else blob_of_run_[root] += length;
  }
  std::size_t pixels_before = 0;
  for (std::size_t i = 0; i < count_; ++i) {
    const std::uint32_t root = parent_[i];
    // A root's entry turns from its component's area into its blob index before its other runs
    // read it.
    const std::int32_t index = root == i ? open_blob(i, params.min_area, blobs, counters) : blob_of_run_[root];
    blob_of_run_[i] = index;
    const PixelRun& run = runs_[i];
    const std::size_t run_start = pixels_before;
    pixels_before += static_cast<std::size_t>(run.x_end - run.x_begin);
    if (index != kNoBlob) add_run_to_blob(run, intensity(run, run_start), blobs[static_cast<std::size_t>(index)]);
  }
  counters.blobs_dropped = blobs.dropped();
}

template <typename RunIntensity>
void RunLabeller::add_run_to_blob(const PixelRun& run, const RunIntensity& row, Blob& blob) {
  const auto length = static_cast<std::uint64_t>(run.x_end - run.x_begin);
  const auto y = static_cast<std::uint64_t>(run.y);
  blob.area += static_cast<std::uint32_t>(length);
  blob.x_min = std::min(blob.x_min, run.x_begin);
  blob.x_max = std::max(blob.x_max, run.x_end - 1);
  blob.y_max = run.y;  // runs arrive in raster order
  blob.sum_x += static_cast<std::uint64_t>(run.x_begin + run.x_end - 1) * length / 2;
  blob.sum_y += y * length;
  std::uint64_t s0 = 0, s1 = 0, s2 = 0;
  std::uint32_t peak = blob.peak;
  const int x_end = run.x_end;
  for (int x = run.x_begin; x < x_end; ++x) {
    const std::uint32_t value = row(x);
    const auto ux = static_cast<std::uint64_t>(x);
    s0 += value;
    s1 += value * ux;
    s2 += value * ux * ux;
    peak = std::max(peak, value);
  }
  blob.peak = peak;
  blob.sum_i += s0;
  blob.sum_ix += s1;
  blob.sum_iy += s0 * y;
  blob.sum_ixx += s2;
  blob.sum_iyy += s0 * y * y;
  blob.sum_ixy += s1 * y;
}

}  // namespace irloc
