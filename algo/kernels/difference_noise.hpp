#pragma once
// The noise of a strobe pair's difference, estimated once per pair and shared by every consumer
// (the shared pair pass, pair_pass.hpp), so that one config serves 8-, 10- and 12-bit sensors and
// dim or bright ceilings without a threshold tuned per ceiling.
//
// On a sparse IR difference nearly every pixel is background: the median m and upper quartile q75
// of max(on - off, 0) give the noise sigma = (q75 - m) / 0.6745 (the upper half of a Gaussian,
// which stays valid when the LED-lit ceiling makes the background difference positive and when
// half of it saturates at 0). A foreground threshold is then m + k * sigma for the consumer's k.
// The histogram has one grey level per bin (differences above 1022 share the last bin); only
// evenly spaced rows are read, and of their histogram only the bins the two quantiles need.

#include <array>
#include <cstdint>

#include "algo/core/image_view.hpp"
#include "algo/kernels/auto_threshold.hpp"

namespace irloc {

struct DifferenceNoise {
  double median = 0;  // of max(on - off, 0), grey levels
  double sigma = 0;   // >= 0.5 once estimated; 0 when nothing was sampled

  // median + sigmas * sigma, rounded to the nearest grey level, at least min_threshold.
  std::uint32_t threshold(double sigmas, std::uint32_t min_threshold) const;
};

class DifferenceNoiseEstimator {
 public:
  // rows: how many evenly spaced rows of a frame of the given height are read (every
  // max(1, height / rows)-th row).
  DifferenceNoiseEstimator(int height, int rows);

  // Allocates nothing.
  DifferenceNoise estimate(ImageView8 on, ImageView8 off);
  DifferenceNoise estimate(ImageView16 on, ImageView16 off);

 private:
  template <typename View>
  DifferenceNoise estimate_in(View on, View off, HistogramShape shape);
  DifferenceNoise from_histogram(int bins) const;

  // Windows of kDifferenceBinWindow bins counted in vector lanes before the rest is counted one
  // pixel at a time: up to a difference of 128 grey levels, each window costing a few percent of the
  // pixel-at-a-time count.
  static constexpr int kMaxBinWindows = 16;

  int row_step_;
  // One grey level per bin, larger differences in the last (8-bit frames use the first 256).
  std::array<std::uint32_t, 1024> bins_{};
};

}  // namespace irloc
