#include "algo/kernels/run_labeller.hpp"

#include <cassert>

namespace irloc {

RunLabeller::RunLabeller(std::size_t max_runs) : runs_(max_runs), parent_(max_runs), blob_of_run_(max_runs) {}

void RunLabeller::begin_frame() {
  count_ = 0;
  runs_dropped_ = 0;
  row_y_ = -2;
  row_begin_ = above_begin_ = above_end_ = above_cursor_ = 0;
}

std::int32_t RunLabeller::open_blob(std::size_t run, std::uint32_t min_area, BlobList& blobs, BlobCounters& counters) {
  ++counters.components;
  if (static_cast<std::uint32_t>(blob_of_run_[run]) < min_area) {
    ++counters.blobs_too_small;
    return kNoBlob;
  }
  if (!blobs.push_back(Blob{})) return kNoBlob;
  Blob& blob = blobs.back();
  blob.x_min = runs_[run].x_begin;
  blob.x_max = runs_[run].x_end - 1;
  blob.y_min = blob.y_max = runs_[run].y;
  return static_cast<std::int32_t>(blobs.size() - 1);
}

void RunLabeller::paint_labels(ImageView<std::int32_t> labels) const {
  for (int y = 0; y < labels.height(); ++y) std::fill_n(labels.row(y), labels.width(), 0);
  for (std::size_t i = 0; i < count_; ++i) {
    if (blob_of_run_[i] == kNoBlob) continue;
    const PixelRun& run = runs_[i];
    assert(run.y < labels.height() && run.x_end <= labels.width());
    std::fill(labels.row(run.y) + run.x_begin, labels.row(run.y) + run.x_end, blob_of_run_[i] + 1);
  }
}

}  // namespace irloc
