#include "algo/kernels/auto_threshold.hpp"

#include <algorithm>
#include <cassert>

#include "algo/kernels/simd_row.hpp"

namespace irloc {
namespace {

__extension__ typedef unsigned __int128 Uint128;

// The bins of a stretch of kStretch pixels are computed in vectors first (saturating difference,
// shift, clamp to the last bin), so that only the increments are scalar. Pixel k of a stretch is
// counted in copy k % kCopies of the histogram (bins holds kCopies of them side by side); the
// copies after the first are cleared first and summed into it at the end.
template <int kCopies, typename Pixel>
void accumulate_difference(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step, HistogramShape shape,
                           std::span<std::uint32_t> bins) {
  assert(on.same_size(off.width(), off.height()));
  assert(static_cast<int>(bins.size()) == kCopies * shape.bins() && row_step >= 1);
  const auto copy_size = static_cast<std::size_t>(shape.bins());
  std::fill(bins.begin() + static_cast<std::ptrdiff_t>(copy_size), bins.end(), 0u);
  constexpr int kLanes = simd::kLanes<Pixel>;
  constexpr int kStretch = 8 * kLanes;
  const int shift = shape.shift();
  // bins() <= 4096 fits a Pixel lane for 16-bit pixels; for 8-bit ones the last bin is <= 255.
  const Pixel last = static_cast<Pixel>(shape.bins() - 1);
  const simd::Vec<Pixel> last_lanes = simd::Vec<Pixel>{} + last;
  static_assert(kStretch % kCopies == 0);
  Pixel stretch[kStretch];
  std::uint32_t* const counts = bins.data();
  const int width = on.width();
  const auto row_bytes = static_cast<std::size_t>(width) * sizeof(Pixel);
  for (int y = 0; y < on.height(); y += row_step) {
    const Pixel* a = on.row(y);
    const Pixel* b = off.row(y);
    // Rows far apart are no stream the hardware prefetcher follows: the next sampled row is
    // fetched while this one is counted.
    if (row_step > 1 && y + row_step < on.height()) {
      const char* next_a = reinterpret_cast<const char*>(on.row(y + row_step));
      const char* next_b = reinterpret_cast<const char*>(off.row(y + row_step));
      for (std::size_t offset = 0; offset < row_bytes; offset += 64) {
        __builtin_prefetch(next_a + offset);
        __builtin_prefetch(next_b + offset);
      }
    }
    int x = 0;
    for (; x + kStretch <= width; x += kStretch) {
      for (int k = 0; k < kStretch; k += kLanes) {
        simd::Vec<Pixel> bin = simd::vector_saturating_subtract(simd::load(a + x + k), simd::load(b + x + k));
        if (shift > 0) bin >>= shift;  // 8-bit lanes have no vector shift: skipped where it is 0
        simd::store(stretch + k, simd::vector_min(bin, last_lanes));
      }
      for (int k = 0; k < kStretch; k += kCopies) {
#pragma GCC unroll 4
        for (int copy = 0; copy < kCopies; ++copy) ++counts[static_cast<std::size_t>(copy) * copy_size + stretch[k + copy]];
      }
    }
    for (; x < width; ++x) {
      const auto bin = static_cast<Pixel>(simd::saturating_subtract(a[x], b[x]) >> shift);
      ++bins[std::min(bin, last)];
    }
  }
  for (int copy = 1; copy < kCopies; ++copy) {
    const std::uint32_t* const from = counts + static_cast<std::size_t>(copy) * copy_size;
    for (std::size_t bin = 0; bin < copy_size; ++bin) counts[bin] += from[bin];
  }
}

// Between-class variance of the split {<= t} | {> t}, up to the constant factor 1/N^2:
// (N * S1 - S * W1)^2 / (W1 * W2), kept as an exact fraction.
struct SplitScore {
  Uint128 numerator;           // < 2^120
  std::uint64_t denominator;   // > 0, < 2^48
};

// a > b for fractions with a 128-bit numerator and a denominator below 2^48: compare the integer
// quotients, then the remainders cross-multiplied (each < 2^48, so the products fit 2^96).
bool greater(const SplitScore& a, const SplitScore& b) {
  const Uint128 qa = a.numerator / a.denominator;
  const Uint128 qb = b.numerator / b.denominator;
  if (qa != qb) return qa > qb;
  const Uint128 ra = a.numerator % a.denominator;
  const Uint128 rb = b.numerator % b.denominator;
  return ra * b.denominator > rb * a.denominator;
}

}  // namespace

void accumulate_difference_histogram(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape,
                                     std::span<std::uint32_t> bins) {
  accumulate_difference<1>(on, off, row_step, shape, bins);
}
void accumulate_difference_histogram(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape,
                                     std::span<std::uint32_t> bins) {
  accumulate_difference<1>(on, off, row_step, shape, bins);
}
void accumulate_difference_histogram_interleaved(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape,
                                                 std::span<std::uint32_t> bins) {
  accumulate_difference<kHistogramCopies>(on, off, row_step, shape, bins);
}
void accumulate_difference_histogram_interleaved(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape,
                                                 std::span<std::uint32_t> bins) {
  accumulate_difference<kHistogramCopies>(on, off, row_step, shape, bins);
}

void accumulate_histogram(ImageView8 image, HistogramShape shape, std::span<std::uint32_t> bins) {
  assert(static_cast<int>(bins.size()) == shape.bins());
  const int shift = shape.shift();
  for (int y = 0; y < image.height(); ++y) {
    const std::uint8_t* row = image.row(y);
    for (int x = 0; x < image.width(); ++x) ++bins[row[x] >> shift];
  }
}

int otsu_threshold(std::span<const std::uint32_t> bins) {
  assert(bins.size() <= 4096);
  std::uint64_t total_count = 0;  // N < 2^24 (see the header)
  std::uint64_t total_sum = 0;    // S = sum of bin * count < 2^36
  for (std::size_t i = 0; i < bins.size(); ++i) {
    total_count += bins[i];
    total_sum += static_cast<std::uint64_t>(i) * bins[i];
  }
  assert(total_count < (std::uint64_t{1} << 24));
  int best = 0;
  SplitScore best_score{0, 1};
  std::uint64_t count_below = 0;  // W1
  std::uint64_t sum_below = 0;    // S1
  for (std::size_t i = 0; i < bins.size(); ++i) {
    count_below += bins[i];
    sum_below += static_cast<std::uint64_t>(i) * bins[i];
    const std::uint64_t count_above = total_count - count_below;  // W2
    if (count_below == 0 || count_above == 0) continue;
    // q1 q2 (mu1 - mu2)^2 = (N S1 - S W1)^2 / (N^2 W1 W2); N^2 is common to every split.
    const std::uint64_t lhs = total_count * sum_below;
    const std::uint64_t rhs = total_sum * count_below;
    const std::uint64_t gap = lhs > rhs ? lhs - rhs : rhs - lhs;  // < 2^60
    const SplitScore score{static_cast<Uint128>(gap) * gap, count_below * count_above};
    if (greater(score, best_score)) {
      best_score = score;
      best = static_cast<int>(i);
    }
  }
  return best;
}

int noise_floor_threshold(std::span<const std::uint32_t> bins, NoiseFloorParams params) {
  std::uint64_t total = 0;
  for (const std::uint32_t count : bins) total += count;
  const std::uint64_t wanted = (total * params.quantile_ppm + 999'999) / 1'000'000;
  std::uint64_t cumulative = 0;
  int bin = 0;
  for (; bin < static_cast<int>(bins.size()) - 1; ++bin) {
    cumulative += bins[static_cast<std::size_t>(bin)];
    if (cumulative >= wanted) break;
  }
  return std::min(bin + params.margin_bins, static_cast<int>(bins.size()) - 1);
}

int automatic_threshold(std::span<const std::uint32_t> bins, NoiseFloorParams params) {
  return std::max(otsu_threshold(bins), noise_floor_threshold(bins, params));
}

}  // namespace irloc
