#include "algo/kernels/blob_labeller.hpp"

#include <algorithm>
#include <cassert>

#include "algo/kernels/run_scan.hpp"
#include "algo/kernels/simd_row.hpp"

namespace irloc {

BlobLabeller::BlobLabeller(std::size_t max_runs) : runs_(max_runs) {}

std::uint32_t BlobLabeller::extract_runs(ImageView8 mask) {
  runs_.begin_frame();
  std::uint32_t foreground = 0;
  for (int y = 0; y < mask.height(); ++y) {
    const std::uint8_t* row = mask.row(y);
    if (simd::max_value(row, mask.width()) == 0) continue;
    foreground += detail::scan_runs(row, mask.width(), [&](int begin, int end) { runs_.add_run(y, begin, end); });
  }
  return foreground;
}

template <typename Pixel>
void BlobLabeller::collect_with(ImageView<const Pixel> intensity, BlobParams params, BlobList& blobs,
                                BlobCounters& counters) {
  const auto row_of = [&](const PixelRun& run, std::size_t) {
    return [row = intensity.row(run.y)](int x) { return std::max<std::uint32_t>(row[x], 1); };
  };
  runs_.collect(row_of, params, blobs, counters);
}

BlobCounters BlobLabeller::label(ImageView8 mask, BlobParams params, BlobList& blobs) {
  BlobCounters counters;
  counters.foreground_pixels = extract_runs(mask);
  const auto intensity = [&](const PixelRun& run, std::size_t) {
    return [row = mask.row(run.y)](int x) { return static_cast<std::uint32_t>(row[x]); };
  };
  runs_.collect(intensity, params, blobs, counters);
  return counters;
}

BlobCounters BlobLabeller::label(ImageView8 mask, ImageView8 intensity, BlobParams params, BlobList& blobs) {
  assert(mask.same_size(intensity.width(), intensity.height()));
  BlobCounters counters;
  counters.foreground_pixels = extract_runs(mask);
  collect_with(intensity, params, blobs, counters);
  return counters;
}

BlobCounters BlobLabeller::label(ImageView8 mask, ImageView16 intensity, BlobParams params, BlobList& blobs) {
  assert(mask.same_size(intensity.width(), intensity.height()));
  BlobCounters counters;
  counters.foreground_pixels = extract_runs(mask);
  collect_with(intensity, params, blobs, counters);
  return counters;
}

}  // namespace irloc
