#include "algo/kernels/blob_labeller.hpp"

#include <algorithm>
#include <cassert>

#include "algo/kernels/run_scan.hpp"
#include "algo/kernels/simd_row.hpp"

namespace irloc {

BlobLabeller::BlobLabeller(std::size_t max_runs) : runs_(max_runs) {}

template <typename RowIntensity>
BlobCounters BlobLabeller::label_with(ImageView8 mask, const RowIntensity& row_intensity, BlobParams params,
                                      BlobList& blobs) {
  BlobCounters counters;
  runs_.begin_frame();
  for (int y = 0; y < mask.height(); ++y) {
    const std::uint8_t* row = mask.row(y);
    if (simd::max_value(row, mask.width()) == 0) continue;
    const auto intensity = row_intensity(y);
    counters.foreground_pixels += detail::scan_runs(
        row, mask.width(), [&](int begin, int end) { runs_.add_run(y, begin, end, run_sums(begin, end, intensity)); });
  }
  runs_.collect(params, blobs, counters);
  return counters;
}

BlobCounters BlobLabeller::label(ImageView8 mask, BlobParams params, BlobList& blobs) {
  const auto mask_values = [&](int y) {
    return [row = mask.row(y)](int x) { return static_cast<std::uint32_t>(row[x]); };
  };
  return label_with(mask, mask_values, params, blobs);
}

template <typename Pixel>
BlobCounters BlobLabeller::label_image(ImageView8 mask, ImageView<const Pixel> intensity, BlobParams params,
                                       BlobList& blobs) {
  assert(mask.same_size(intensity.width(), intensity.height()));
  const auto image_values = [&](int y) {
    return [row = intensity.row(y)](int x) { return std::max<std::uint32_t>(row[x], 1); };
  };
  return label_with(mask, image_values, params, blobs);
}

BlobCounters BlobLabeller::label(ImageView8 mask, ImageView8 intensity, BlobParams params, BlobList& blobs) {
  return label_image(mask, intensity, params, blobs);
}

BlobCounters BlobLabeller::label(ImageView8 mask, ImageView16 intensity, BlobParams params, BlobList& blobs) {
  return label_image(mask, intensity, params, blobs);
}

}  // namespace irloc
