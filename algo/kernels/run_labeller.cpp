#include "algo/kernels/run_labeller.hpp"

#include <cassert>

namespace irloc {

RunLabeller::RunLabeller(std::size_t max_runs)
    : runs_(max_runs), parent_(max_runs), component_of_root_(max_runs), components_(max_runs) {}

void RunLabeller::begin_frame() {
  count_ = 0;
  component_count_ = 0;
  runs_dropped_ = 0;
  row_y_ = -2;
  row_begin_ = above_begin_ = above_end_ = above_cursor_ = 0;
}

void RunLabeller::open_component(std::uint32_t run) {
  component_of_root_[run] = static_cast<std::int32_t>(component_count_);
  Blob& component = components_[component_count_++];
  component = Blob{};
  component.x_min = runs_[run].x_begin;
  component.x_max = runs_[run].x_end - 1;
  component.y_min = runs_[run].y;
}

std::uint32_t RunLabeller::combine(std::uint32_t root_a, std::uint32_t root_b) {
  const std::uint32_t first = std::min(root_a, root_b);
  const std::uint32_t later = std::max(root_a, root_b);
  parent_[later] = first;
  Blob& into = components_[static_cast<std::size_t>(component_of_root_[first])];
  const Blob& from = components_[static_cast<std::size_t>(component_of_root_[later])];
  into.area += from.area;
  into.x_min = std::min(into.x_min, from.x_min);
  into.x_max = std::max(into.x_max, from.x_max);
  into.y_max = std::max(into.y_max, from.y_max);  // y_min: the first run's row, the earliest
  into.sum_x += from.sum_x;
  into.sum_y += from.sum_y;
  into.sum_i += from.sum_i;
  into.sum_ix += from.sum_ix;
  into.sum_iy += from.sum_iy;
  into.sum_ixx += from.sum_ixx;
  into.sum_iyy += from.sum_iyy;
  into.sum_ixy += from.sum_ixy;
  into.peak = std::max(into.peak, from.peak);
  return first;
}

void RunLabeller::collect(BlobParams params, BlobList& blobs, BlobCounters& counters) {
  blobs.clear();
  counters.runs = static_cast<std::uint32_t>(count_);
  counters.runs_dropped = runs_dropped_;
  counters.components = 0;
  counters.blobs_too_small = 0;
  // Roots in index order: components in raster order of their first pixel.
  for (std::size_t i = 0; i < count_; ++i) {
    if (parent_[i] != i) continue;
    ++counters.components;
    const Blob& component = components_[static_cast<std::size_t>(component_of_root_[i])];
    std::int32_t blob = kNoBlob;
    if (component.area < params.min_area) {
      ++counters.blobs_too_small;
    } else if (blobs.push_back(component)) {
      blob = static_cast<std::int32_t>(blobs.size() - 1);
    }
    component_of_root_[i] = blob;
  }
  counters.blobs_dropped = blobs.dropped();
}

void RunLabeller::paint_labels(ImageView<std::int32_t> labels) const {
  for (int y = 0; y < labels.height(); ++y) std::fill_n(labels.row(y), labels.width(), 0);
  for (std::size_t i = 0; i < count_; ++i) {
    std::size_t root = i;
    while (parent_[root] != root) root = parent_[root];
    if (component_of_root_[root] == kNoBlob) continue;
    const PixelRun& run = runs_[i];
    assert(run.y < labels.height() && run.x_end <= labels.width());
    std::fill(labels.row(run.y) + run.x_begin, labels.row(run.y) + run.x_end, component_of_root_[root] + 1);
  }
}

}  // namespace irloc
