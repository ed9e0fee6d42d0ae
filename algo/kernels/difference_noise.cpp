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

DifferenceNoise DifferenceNoiseEstimator::estimate(ImageView8 on, ImageView8 off) {
  std::fill_n(bins_.begin(), 256, 0u);
  const HistogramShape shape{8, 8};
  accumulate_sparse_difference_histogram(on, off, row_step_, shape, std::span<std::uint32_t>(bins_.data(), 256));
  return from_histogram(256);
}

DifferenceNoise DifferenceNoiseEstimator::estimate(ImageView16 on, ImageView16 off) {
  std::fill_n(bins_.begin(), 1024, 0u);
  const HistogramShape shape{10, 10};  // one bin per grey level up to 1022, whatever the depth
  accumulate_sparse_difference_histogram(on, off, row_step_, shape, bins_);
  return from_histogram(1024);
}

}  // namespace irloc
