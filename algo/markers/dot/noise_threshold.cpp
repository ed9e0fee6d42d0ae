#include "algo/markers/dot/noise_threshold.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "algo/kernels/auto_threshold.hpp"

namespace irloc::dot {
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

std::uint32_t NoiseThreshold::from_histogram(int bins) {
  const std::span<const std::uint32_t> used(bins_.data(), static_cast<std::size_t>(bins));
  std::uint64_t total = 0;
  for (const std::uint32_t count : used) total += count;
  if (total == 0) return min_threshold_;
  // Differences saturated at 0 all sit in bin 0, so the median is not taken below 0.
  const double median = std::max(0.0, quantile(used, total, 0.5));
  const double upper = quantile(used, total, 0.75);
  last_sigma_ = std::max(0.5, (upper - median) / 0.6745);
  const double threshold = median + sigmas_ * last_sigma_;
  return std::max(min_threshold_, static_cast<std::uint32_t>(std::lround(threshold)));
}

std::uint32_t NoiseThreshold::estimate(ImageView8 on, ImageView8 off) {
  bins_.fill(0);
  const HistogramShape shape{8, 8};
  accumulate_difference_histogram(on, off, row_step_, shape, std::span<std::uint32_t>(bins_.data(), 256));
  return from_histogram(256);
}

std::uint32_t NoiseThreshold::estimate(ImageView16 on, ImageView16 off) {
  bins_.fill(0);
  const HistogramShape shape{10, 10};  // one bin per grey level up to 1022, whatever the depth
  accumulate_difference_histogram(on, off, row_step_, shape, bins_);
  return from_histogram(1024);
}

}  // namespace irloc::dot
