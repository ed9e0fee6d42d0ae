#pragma once
// Histograms of the strobe difference and thresholds chosen from them, so that nobody has to
// tune a threshold per ceiling.
//
// A histogram has 2^k bins (k <= 12) over pixel values of value_bits bits (8 for 8-bit frames;
// 10, 12 or 16 for 16-bit ones): bin = value >> (value_bits - k), values above the depth go to
// the last bin. Thresholds come back as a bin index t; foreground is "bin > t", which is
// "pixel > threshold_value(t)" in pixel units.

#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"

namespace irloc {

struct HistogramShape {
  int value_bits = 8;  // significant bits of a pixel
  int bin_bits = 8;    // log2 of the number of bins; bin_bits <= value_bits, <= 12

  int bins() const { return 1 << bin_bits; }
  int shift() const { return value_bits - bin_bits; }
  // The largest pixel value whose bin is <= bin: pixel > threshold_value(t) <=> bin > t.
  std::uint32_t threshold_value(int bin) const { return ((static_cast<std::uint32_t>(bin) + 1) << shift()) - 1; }
};

// Adds the histogram of max(on - off, 0) to bins (bins.size() == shape.bins(); not cleared).
// Only every row_step-th row is read (1: all), which keeps an occasional re-estimate cheap.
void accumulate_difference_histogram(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape,
                                     std::span<std::uint32_t> bins);
void accumulate_difference_histogram(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape,
                                     std::span<std::uint32_t> bins);
// The same histogram in parts, for a sparse strobe difference, where nearly every pixel falls in
// the lowest bins: a window adds to the kDifferenceBinWindow bins from first_bin (a multiple of
// kDifferenceBinWindow below shape.bins()) only, counted in vector lanes; the large part adds to
// the bins from first_bin up (1 <= first_bin <= shape.bins()), one pixel at a time. Windows from 0
// up to some first_bin and the large part from there add what accumulate_difference_histogram
// adds; a consumer that needs only the lowest bins (quantiles they already hold) stops early.
// shape.bins() >= kDifferenceBinWindow.
inline constexpr int kDifferenceBinWindow = 8;
void accumulate_difference_bin_window(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins);
void accumulate_difference_bin_window(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins);
void accumulate_large_difference_bins(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins);
void accumulate_large_difference_bins(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins);
// Adds the histogram of an image (e.g. an already computed difference image).
void accumulate_histogram(ImageView8 image, HistogramShape shape, std::span<std::uint32_t> bins);

// Otsu's threshold: the bin t that maximises the between-class variance of {<= t} and {> t},
// computed exactly in integers (the first t on ties, as cv::THRESH_OTSU). 0 for an empty or
// single-valued histogram. Limits: at most 4096 bins and fewer than 2^24 pixels (4096 x 4096).
int otsu_threshold(std::span<const std::uint32_t> bins);

// Noise floor: the smallest bin at or below which at least quantile_ppm (parts per million) of
// the pixels lie, plus margin_bins. On a sparse IR difference nearly every pixel is sensor noise,
// so a high quantile measures the noise and the margin keeps it out of the foreground.
struct NoiseFloorParams {
  std::uint32_t quantile_ppm = 999'000;
  int margin_bins = 4;
};
int noise_floor_threshold(std::span<const std::uint32_t> bins, NoiseFloorParams params);

// The larger of the two: Otsu separates markers from background when both are present; the noise
// floor stops Otsu from splitting pure noise in half when no marker is in view.
int automatic_threshold(std::span<const std::uint32_t> bins, NoiseFloorParams params);

}  // namespace irloc
