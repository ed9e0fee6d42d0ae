#include "algo/markers/square/tape_mask.hpp"

#include <algorithm>
#include <span>

#include "algo/kernels/auto_threshold.hpp"
#include "algo/kernels/difference.hpp"

namespace irloc {
namespace {

// Tape covers about 1 % of a frame, so the noise floor is read well below that fraction.
constexpr NoiseFloorParams kNoiseFloor{.quantile_ppm = 970'000, .margin_bins = 4};
// Every 4th row is enough for the histogram.
constexpr int kHistogramRowStep = 4;

}  // namespace

TapeMask::TapeMask(int x, int y, int width, int height, int element_radius, std::uint16_t threshold)
    : x_(x),
      y_(y),
      fixed_threshold_(threshold),
      thin_lines_(width, height, StructuringElement{ElementShape::square, element_radius}),
      difference8_(width, height),
      difference16_(width, height),
      mask_(width, height) {}

template <typename Pixel>
std::uint16_t TapeMask::extract_depth(ImageView<const Pixel> on_frame, ImageView<const Pixel> off_frame) {
  const ImageView<const Pixel> on = on_frame.region(x_, y_, mask_.width(), mask_.height());
  const ImageView<const Pixel> off = off_frame.region(x_, y_, mask_.width(), mask_.height());
  constexpr bool kWide = sizeof(Pixel) == 2;
  std::uint16_t threshold = fixed_threshold_;
  if (threshold == 0) {
    const HistogramShape shape{.value_bits = kWide ? 16 : 8, .bin_bits = kWide ? 12 : 8};
    const std::span<std::uint32_t> bins(histogram_.data(), static_cast<std::size_t>(shape.bins()));
    std::fill(bins.begin(), bins.end(), 0u);
    accumulate_difference_histogram(on, off, kHistogramRowStep, shape, bins);
    threshold = static_cast<std::uint16_t>(shape.threshold_value(automatic_threshold(bins, kNoiseFloor)));
  }
  if constexpr (kWide) {
    subtract_saturating(on, off, difference16_.view());
    thin_lines_.extract(ImageView16(difference16_.view()), threshold, mask_.view());
  } else {
    subtract_saturating(on, off, difference8_.view());
    thin_lines_.extract(ImageView8(difference8_.view()), static_cast<std::uint8_t>(std::min<std::uint16_t>(threshold, 255)),
                        mask_.view());
  }
  return threshold;
}

std::uint16_t TapeMask::extract(const GrayImageView& on, const GrayImageView& off) {
  if (const auto* on8 = std::get_if<ImageView8>(&on)) return extract_depth(*on8, std::get<ImageView8>(off));
  return extract_depth(std::get<ImageView16>(on), std::get<ImageView16>(off));
}

}  // namespace irloc
