#include "algo/kernels/auto_threshold.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

#include "algo/kernels/simd_row.hpp"
#include "algo/kernels/wide_vectors.hpp"

namespace irloc {
namespace {

__extension__ typedef unsigned __int128 Uint128;

// Rows far apart are no stream the hardware prefetcher follows: the next sampled row is fetched
// while this one is counted.
template <typename Pixel>
void prefetch_next_row(ImageView<const Pixel> on, ImageView<const Pixel> off, int y, int row_step) {
  if (row_step == 1 || y + row_step >= on.height()) return;
  const auto row_bytes = static_cast<std::size_t>(on.width()) * sizeof(Pixel);
  const char* next_a = reinterpret_cast<const char*>(on.row(y + row_step));
  const char* next_b = reinterpret_cast<const char*>(off.row(y + row_step));
  for (std::size_t offset = 0; offset < row_bytes; offset += 64) {
    __builtin_prefetch(next_a + offset);
    __builtin_prefetch(next_b + offset);
  }
}

// The bins of pixels [x, x + n) of a row pair: saturating difference, shift, clamp to the last bin.
template <typename Pixel>
simd::Vec<Pixel> difference_bins(const Pixel* a, const Pixel* b, int shift, simd::Vec<Pixel> last_lanes) {
  simd::Vec<Pixel> bin = simd::vector_saturating_subtract(simd::load(a), simd::load(b));
  if (shift > 0) bin >>= shift;  // 8-bit lanes have no vector shift: skipped where it is 0
  return simd::vector_min(bin, last_lanes);
}

template <typename Pixel>
void accumulate_difference(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step, HistogramShape shape,
                           std::span<std::uint32_t> bins) {
  assert(on.same_size(off.width(), off.height()));
  assert(static_cast<int>(bins.size()) == shape.bins() && row_step >= 1);
  constexpr int kLanes = simd::kLanes<Pixel>;
  const int shift = shape.shift();
  // bins() <= 4096 fits a Pixel lane for 16-bit pixels; for 8-bit ones the last bin is <= 255.
  const Pixel last = static_cast<Pixel>(shape.bins() - 1);
  const simd::Vec<Pixel> last_lanes = simd::Vec<Pixel>{} + last;
  Pixel lanes[kLanes];
  for (int y = 0; y < on.height(); y += row_step) {
    const Pixel* a = on.row(y);
    const Pixel* b = off.row(y);
    int x = 0;
    for (; x + kLanes <= on.width(); x += kLanes) {
      simd::store(lanes, difference_bins(a + x, b + x, shift, last_lanes));
      for (const Pixel bin : lanes) ++bins[bin];
    }
    for (; x < on.width(); ++x) ++bins[std::min(static_cast<Pixel>(simd::saturating_subtract(a[x], b[x]) >> shift), last)];
  }
}

// The bins [first_bin, first_bin + kDifferenceBinWindow) in vector lanes, so that no increment
// waits on another: lane counter k adds 1 where a vector's bin is first_bin + k (an equality
// compare of bin - first_bin, which wraps far above the window for the bins below it, is all ones
// there, and is subtracted). The counters are emptied into the histogram before they can wrap.
template <int kBytes, typename Pixel>
__attribute__((always_inline)) inline void count_bin_window(ImageView<const Pixel> on, ImageView<const Pixel> off,
                                                            int row_step, HistogramShape shape, int first_bin,
                                                            std::uint32_t* bins) {
  using V = wide::Vec<Pixel, kBytes>;
  constexpr int kLanes = wide::kLanes<Pixel, kBytes>;
  constexpr int kMaxVectors = std::numeric_limits<Pixel>::max();  // a lane counter gains <= 1 a vector
  const int shift = shape.shift();
  const auto last = static_cast<Pixel>(shape.bins() - 1);
  const V last_lanes = V{} + last;
  const V first_lanes = V{} + static_cast<Pixel>(first_bin);
  std::uint32_t* const window = bins + first_bin;
  V counts[kDifferenceBinWindow] = {};
  int vectors = 0;
  const auto empty_counts = [&] {
    for (int k = 0; k < kDifferenceBinWindow; ++k) {
      Pixel lanes[kLanes];
      wide::store(lanes, counts[k]);
      for (const Pixel count : lanes) window[k] += count;
      counts[k] = V{};
    }
    vectors = 0;
  };
  // The vector at pixel x of a row pair; counted are the lanes set in keep.
  const auto count_vector = [&](const Pixel* a, const Pixel* b, int x, const V& keep) __attribute__((always_inline)) {
    const V on_lanes = wide::load<V>(a + x);
    const V off_lanes = wide::load<V>(b + x);
    V bin = on_lanes - (on_lanes < off_lanes ? on_lanes : off_lanes);
    if (shift > 0) bin >>= shift;  // 8-bit lanes have no vector shift: skipped where it is 0
    const V offset = (bin < last_lanes ? bin : last_lanes) - first_lanes;
#pragma GCC unroll 8
    for (int k = 0; k < kDifferenceBinWindow; ++k) {
      counts[k] -= reinterpret_cast<V>(offset == static_cast<Pixel>(k)) & keep;
    }
    if (++vectors == kMaxVectors) empty_counts();
  };
  const V every_lane = V{} + static_cast<Pixel>(~Pixel{0});
  const int width = on.width();
  for (int y = 0; y < on.height(); y += row_step) {
    prefetch_next_row(on, off, y, row_step);
    const Pixel* a = on.row(y);
    const Pixel* b = off.row(y);
    int x = 0;
    for (; x + kLanes <= width; x += kLanes) count_vector(a, b, x, every_lane);
    if (x < width && width >= kLanes) {  // the rest: the row's last vector, its overlap counted once
      count_vector(a, b, width - kLanes, wide::last_lanes<V>(width - x));
      x = width;
    }
    for (; x < width; ++x) {
      const int offset = std::min(simd::saturating_subtract(a[x], b[x]) >> shift, static_cast<int>(last)) - first_bin;
      if (offset >= 0 && offset < kDifferenceBinWindow) ++window[offset];
    }
  }
  empty_counts();
}

template <typename Pixel>
struct BinWindow {
  IRLOC_WIDE_KERNEL_16 static void count(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step,
                                         HistogramShape shape, int first_bin, std::uint32_t* bins) {
    count_bin_window<16>(on, off, row_step, shape, first_bin, bins);
  }
  IRLOC_WIDE_KERNEL_32(static void count(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step,
                                         HistogramShape shape, int first_bin, std::uint32_t* bins) {
    count_bin_window<32>(on, off, row_step, shape, first_bin, bins);
  })
  IRLOC_WIDE_KERNEL_64(static void count(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step,
                                         HistogramShape shape, int first_bin, std::uint32_t* bins) {
    count_bin_window<64>(on, off, row_step, shape, first_bin, bins);
  })
};

template <typename Pixel>
void accumulate_window(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step, HistogramShape shape,
                       int first_bin, std::span<std::uint32_t> bins) {
  assert(on.same_size(off.width(), off.height()));
  assert(static_cast<int>(bins.size()) == shape.bins() && row_step >= 1);
  assert(first_bin >= 0 && first_bin % kDifferenceBinWindow == 0 && first_bin < shape.bins());
  BinWindow<Pixel>::count(on, off, row_step, shape, first_bin, bins.data());
}

// The bins from first_bin up: a vector of bins all below it (nearly every one) is skipped after
// one test, the others' lanes are counted one by one.
template <typename Pixel>
void accumulate_large(ImageView<const Pixel> on, ImageView<const Pixel> off, int row_step, HistogramShape shape,
                      int first_bin, std::span<std::uint32_t> bins) {
  assert(on.same_size(off.width(), off.height()));
  assert(static_cast<int>(bins.size()) == shape.bins() && row_step >= 1 && first_bin >= 1 && first_bin <= shape.bins());
  using V = simd::Vec<Pixel>;
  constexpr int kLanes = simd::kLanes<Pixel>;
  const int shift = shape.shift();
  const Pixel last = static_cast<Pixel>(shape.bins() - 1);
  const V last_lanes = V{} + last;
  const auto below = static_cast<Pixel>(first_bin - 1);
  const V below_lanes = V{} + below;
  Pixel lanes[kLanes];
  for (int y = 0; y < on.height(); y += row_step) {
    prefetch_next_row(on, off, y, row_step);
    const Pixel* a = on.row(y);
    const Pixel* b = off.row(y);
    int x = 0;
    for (; x + kLanes <= on.width(); x += kLanes) {
      const V bin = difference_bins(a + x, b + x, shift, last_lanes);
      if (!simd::any_lane(bin - simd::vector_min(bin, below_lanes))) continue;
      simd::store(lanes, bin);
      for (const Pixel lane_bin : lanes) {
        if (lane_bin > below) ++bins[lane_bin];
      }
    }
    for (; x < on.width(); ++x) {
      const Pixel bin = std::min(static_cast<Pixel>(simd::saturating_subtract(a[x], b[x]) >> shift), last);
      if (bin > below) ++bins[bin];
    }
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
  accumulate_difference(on, off, row_step, shape, bins);
}
void accumulate_difference_histogram(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape,
                                     std::span<std::uint32_t> bins) {
  accumulate_difference(on, off, row_step, shape, bins);
}
void accumulate_difference_bin_window(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins) {
  accumulate_window(on, off, row_step, shape, first_bin, bins);
}
void accumulate_difference_bin_window(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins) {
  accumulate_window(on, off, row_step, shape, first_bin, bins);
}
void accumulate_large_difference_bins(ImageView8 on, ImageView8 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins) {
  accumulate_large(on, off, row_step, shape, first_bin, bins);
}
void accumulate_large_difference_bins(ImageView16 on, ImageView16 off, int row_step, HistogramShape shape, int first_bin,
                                      std::span<std::uint32_t> bins) {
  accumulate_large(on, off, row_step, shape, first_bin, bins);
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
