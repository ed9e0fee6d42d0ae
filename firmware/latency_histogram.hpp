#pragma once
// Capture-to-write latencies (the frame's t_ns to the serial write of its pose, on one clock) in
// 10 us bins up to 100 ms; longer ones count in the last bin. Quantiles are bin upper edges, so
// they overstate by at most 10 us. Fixed size, allocates nothing.

#include <array>
#include <cstdint>
#include <optional>

namespace irloc::firmware {

class LatencyHistogram {
 public:
  static constexpr std::int64_t kBinNs = 10'000;
  static constexpr std::size_t kBins = 10'000;

  // Negative latencies (a clock that jumped) are not counted.
  void add(std::int64_t latency_ns);
  std::uint64_t count() const { return count_; }
  // The q-quantile (0 < q <= 1) in milliseconds of the latencies added since `earlier` (a copy of
  // this histogram taken before; null: since the start). Empty when none were.
  std::optional<double> quantile_ms(double q, const LatencyHistogram* earlier = nullptr) const;

 private:
  std::array<std::uint32_t, kBins> bins_{};
  std::uint64_t count_ = 0;
};

}  // namespace irloc::firmware
