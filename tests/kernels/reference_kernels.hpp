#pragma once
// Plain scalar references of the image kernels, one obvious loop each, for the tests that check
// the fast kernels against them and the benchmarks' "before" cases. Test code only (linked into
// tests and benchmarks, never into the product): blobs() allocates.

#include <cstdint>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/kernels/morphology.hpp"
#include "algo/kernels/strobe_check.hpp"

namespace irloc::reference {

template <typename Pixel>
void subtract_saturating(ImageView<const Pixel> on, ImageView<const Pixel> off, ImageView<Pixel> out) {
  for (int y = 0; y < on.height(); ++y) {
    for (int x = 0; x < on.width(); ++x) {
      out.at(x, y) = on.at(x, y) > off.at(x, y) ? static_cast<Pixel>(on.at(x, y) - off.at(x, y)) : Pixel{0};
    }
  }
}

template <typename Pixel>
void threshold_binary(ImageView<const Pixel> in, Pixel threshold, std::uint8_t max_value, MutableImageView8 out) {
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) out.at(x, y) = in.at(x, y) > threshold ? max_value : 0;
  }
}

// Pixels with on - off > noise_level and off - on > noise_level: the scalar strobe check irlocd
// ran as a second pass over every pair before the count was fused into the front end (the
// benchmark's "before").
template <typename Pixel>
StrobeCounts strobe_counts(ImageView<const Pixel> on, ImageView<const Pixel> off, int noise_level) {
  StrobeCounts counts;
  for (int y = 0; y < on.height(); ++y) {
    const Pixel* on_row = on.row(y);
    const Pixel* off_row = off.row(y);
    for (int x = 0; x < on.width(); ++x) {
      const int difference = static_cast<int>(on_row[x]) - static_cast<int>(off_row[x]);
      counts.brighter_on += difference > noise_level ? 1u : 0u;
      counts.brighter_off += difference < -noise_level ? 1u : 0u;
    }
  }
  return counts;
}

// Min (erode) or max (dilate) over the element's pixels inside the image.
void erode(ImageView8 in, StructuringElement element, MutableImageView8 out);
void dilate(ImageView8 in, StructuringElement element, MutableImageView8 out);

// 8-connected components of intensity(x, y) > threshold by flood fill, in raster order of first
// pixel, each with the statistics of blob.hpp (I = the pixel's value).
// labels (optional: pass an empty view to skip) gets 1 + component index, 0 for background.
template <typename Pixel>
std::vector<Blob> blobs(ImageView<const Pixel> intensity, Pixel threshold, ImageView<std::int32_t> labels = {});

}  // namespace irloc::reference
