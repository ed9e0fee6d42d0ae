#include "firmware/latency_histogram.hpp"

#include <algorithm>
#include <cmath>

namespace irloc::firmware {

void LatencyHistogram::add(std::int64_t latency_ns) {
  if (latency_ns < 0) return;
  const std::size_t bin = std::min(static_cast<std::size_t>(latency_ns / kBinNs), kBins - 1);
  ++bins_[bin];
  ++count_;
}

std::optional<double> LatencyHistogram::quantile_ms(double q, const LatencyHistogram* earlier) const {
  const std::uint64_t total = count_ - (earlier ? earlier->count_ : 0);
  if (total == 0) return std::nullopt;
  const auto rank = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(total)));
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < kBins; ++bin) {
    seen += bins_[bin] - (earlier ? earlier->bins_[bin] : 0);
    if (seen >= std::max<std::uint64_t>(rank, 1)) return static_cast<double>((bin + 1) * kBinNs) * 1e-6;
  }
  return static_cast<double>(kBins * kBinNs) * 1e-6;
}

}  // namespace irloc::firmware
