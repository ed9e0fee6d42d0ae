#pragma once
// Plain scalar references of the image kernels, one obvious loop each, for the tests that check
// the fast kernels against them and the benchmarks' "before" cases. Test code only (linked into
// tests and benchmarks, never into the product): blobs() allocates.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/kernels/difference_noise.hpp"
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

// The noise estimate as difference_noise.hpp states it, from the whole histogram of max(on - off,
// 0) over rows 0, row_step, 2 row_step, ... (one grey level per bin, 1023 and above in the last):
// median m and upper quartile q75 interpolated within their bins, sigma = (q75 - m) / 0.6745.
template <typename Pixel>
DifferenceNoise difference_noise(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step) {
  std::vector<std::uint64_t> bins(1024, 0);
  std::uint64_t total = 0;
  for (int y = 0; y < on.height(); y += row_step) {
    for (int x = 0; x < on.width(); ++x) {
      const int difference = std::max(0, static_cast<int>(on.at(x, y)) - static_cast<int>(off.at(x, y)));
      ++bins[static_cast<std::size_t>(std::min(difference, 1023))];
      ++total;
    }
  }
  // Bin b holds the integer b, taken as spread over [b - 1/2, b + 1/2).
  const auto quantile = [&](double fraction) {
    const double wanted = fraction * static_cast<double>(total);
    double cumulative = 0;
    for (std::size_t b = 0; b < bins.size(); ++b) {
      const double next = cumulative + static_cast<double>(bins[b]);
      if (next >= wanted && bins[b] > 0) {
        return static_cast<double>(b) - 0.5 + (wanted - cumulative) / static_cast<double>(bins[b]);
      }
      cumulative = next;
    }
    return static_cast<double>(bins.size());
  };
  DifferenceNoise noise;
  if (total == 0) return noise;
  noise.median = std::max(0.0, quantile(0.5));
  noise.sigma = std::max(0.5, (quantile(0.75) - noise.median) / 0.6745);
  return noise;
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
