#include "algo/kernels/difference_noise.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "algo/kernels/auto_threshold.hpp"

namespace irloc {
namespace {

// The value below which `fraction` of the histogram lies, interpolated within its bin (bin b holds
// the integer b, taken as spread over [b - 1/2, b + 1/2)).
double quantile(std::span<const std::uint32_t> bins, std::uint64_t total, double fraction) {
  const double wanted = fraction * static_cast<double>(total);
  double cumulative = 0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    const double next = cumulative + bins[b];
    if (next >= wanted && bins[b] > 0) return static_cast<double>(b) - 0.5 + (wanted - cumulative) / bins[b];
    cumulative = next;
  }
  return static_cast<double>(bins.size());
}

}  // namespace

std::uint32_t DifferenceNoise::threshold(double sigmas, std::uint32_t min_threshold) const {
  const double value = median + sigmas * sigma;
  return std::max(min_threshold, static_cast<std::uint32_t>(std::lround(value)));
}

DifferenceNoiseEstimator::DifferenceNoiseEstimator(int height, int rows) : row_step_(std::max(1, height / std::max(1, rows))) {}

DifferenceNoise DifferenceNoiseEstimator::from_histogram(int bins) const {
  const std::span<const std::uint32_t> used(bins_.data(), static_cast<std::size_t>(bins));
  std::uint64_t total = 0;
  for (const std::uint32_t count : used) total += count;
  DifferenceNoise noise;
  if (total == 0) return noise;
  // Differences saturated at 0 all sit in bin 0, so the median is not taken below 0.
  noise.median = std::max(0.0, quantile(used, total, 0.5));
  const double upper = quantile(used, total, 0.75);
  noise.sigma = std::max(0.5, (upper - noise.median) / 0.6745);
  return noise;
}

// The quantiles read the bins only up to the one that holds the 75 % quantile. On a sparse IR
// difference that is one of the lowest bins: the bins are counted a window at a time, in vector
// lanes, from 0 up until they hold the quantile, and then the others matter only through their
// sum, the rest of the sampled pixels: it goes to the first of them. Past kMaxBinWindows windows
// (a rereading of the sampled rows each) the others are counted too, one pixel at a time. Either
// way the estimate is the whole histogram's.
template <typename View>
DifferenceNoise DifferenceNoiseEstimator::estimate_in(View on, View off, HistogramShape shape) {
  const std::span<std::uint32_t> bins(bins_.data(), static_cast<std::size_t>(shape.bins()));
  std::fill(bins.begin(), bins.end(), 0u);
  const std::uint64_t sampled = static_cast<std::uint64_t>((on.height() + row_step_ - 1) / row_step_) *
                                static_cast<std::uint64_t>(on.width());
  std::uint64_t counted = 0;
  int first_bin = 0;
  for (int window = 0; window < kMaxBinWindows; ++window) {
    accumulate_difference_bin_window(on, off, row_step_, shape, first_bin, bins);
    for (int b = first_bin; b < first_bin + kDifferenceBinWindow; ++b) counted += bins[static_cast<std::size_t>(b)];
    first_bin += kDifferenceBinWindow;
    if (static_cast<double>(counted) >= 0.75 * static_cast<double>(sampled)) {
      if (first_bin < shape.bins()) bins[static_cast<std::size_t>(first_bin)] = static_cast<std::uint32_t>(sampled - counted);
      return from_histogram(shape.bins());
    }
  }
  accumulate_large_difference_bins(on, off, row_step_, shape, first_bin, bins);
  return from_histogram(shape.bins());
}

DifferenceNoise DifferenceNoiseEstimator::estimate(ImageView8 on, ImageView8 off) {
  return estimate_in(on, off, HistogramShape{8, 8});
}

DifferenceNoise DifferenceNoiseEstimator::estimate(ImageView16 on, ImageView16 off) {
  return estimate_in(on, off, HistogramShape{10, 10});  // one bin per grey level up to 1022, whatever the depth
}

}  // namespace irloc
