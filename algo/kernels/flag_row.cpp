#include "algo/kernels/flag_row.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

#include "algo/kernels/block_bits.hpp"
#include "algo/kernels/wide_vectors.hpp"

namespace irloc::detail {
namespace {

// With m = min(on, off): up = on - m = max(on - off, 0), down = off - m = max(off - on, 0), and
// the flag up - min(up, threshold) = max(on - off - threshold, 0): four lane operations, no
// overflow and no unsigned compare (which SSE2 lacks). With kCount, the lanes where up (down) is
// above the noise level n are counted without a comparison either: min(up, n + 1) - min(up, n) is
// 1 exactly there (0 throughout when n is the largest value, which no difference exceeds), added
// to lane counters that are emptied before they can wrap. So every operation is lane arithmetic
// or min, which every vector width does natively: 32-byte vectors are one AVX2 register or two
// SSE2 / NEON ones (the baseline build), 64-byte vectors one AVX-512 register. (A min against
// the constant 1 would not do: the compiler turns it into a comparison with 0.) Vectors stay
// local to this function (none is passed by value), so its code does not depend on the vector
// calling convention.
// The vector at pixel i: flags stored and ORed into any; with kCount, its lanes set in keep counted.
template <bool kCount, typename V, typename Pixel>
__attribute__((always_inline)) inline void flag_vector(const Pixel* on, const Pixel* off, Pixel* flags, int i,
                                                       const V& limit, const V& noise, const V& noise_above,
                                                       const V& keep, V& any, V& loud_up, V& loud_down) {
  const V a = wide::load<V>(on + i);
  const V b = wide::load<V>(off + i);
  const V low = a < b ? a : b;
  const V up = a - low;
  const V flag = up - (up < limit ? up : limit);
  wide::store(flags + i, flag);
  any |= flag;
  if constexpr (kCount) {
    const V down = b - low;
    loud_up += ((up < noise_above ? up : noise_above) - (up < noise ? up : noise)) & keep;
    loud_down += ((down < noise_above ? down : noise_above) - (down < noise ? down : noise)) & keep;
  }
}

// Adds vectors to the lane counters' tally, and empties them into strobe when one could wrap next.
template <typename Pixel, typename V>
__attribute__((always_inline)) inline void count_vectors(int vectors, StrobeLaneCounts& lanes, StrobeCounts& strobe,
                                                         V& loud_up, V& loud_down) {
  lanes.vectors += vectors;
  if (lanes.vectors < std::numeric_limits<Pixel>::max()) return;
  wide::store(lanes.brighter_on, loud_up);
  wide::store(lanes.brighter_off, loud_down);
  lanes.count_rest<Pixel>(strobe);
  loud_up = V{};
  loud_down = V{};
}

template <int kBytes, typename Pixel, bool kCount>
__attribute__((always_inline)) inline bool flag_row(const Pixel* on, const Pixel* off, int n, Pixel threshold,
                                                    Pixel noise_level, Pixel* flags, StrobeLaneCounts* lanes,
                                                    StrobeCounts* strobe) {
  using V = wide::Vec<Pixel, kBytes>;
  static_assert(kBytes <= StrobeLaneCounts::kBytes);
  constexpr int kLanes = wide::kLanes<Pixel, kBytes>;
  constexpr int kMaxVectors = std::numeric_limits<Pixel>::max();  // before a lane counter could wrap
  const V limit = V{} + threshold;
  const V noise = V{} + noise_level;
  const Pixel above_noise = noise_level == std::numeric_limits<Pixel>::max() ? noise_level : static_cast<Pixel>(noise_level + 1);
  const V noise_above = V{} + above_noise;
  const V every_lane = V{} + static_cast<Pixel>(~Pixel{0});
  V any = {};
  V loud_up = {};
  V loud_down = {};
  if constexpr (kCount) {
    loud_up = wide::load<V>(lanes->brighter_on);
    loud_down = wide::load<V>(lanes->brighter_off);
  }
  int i = 0;
  const int vector_end = n - n % kLanes;
  while (i < vector_end) {
    const int vectors = kCount ? std::min((vector_end - i) / kLanes, kMaxVectors - lanes->vectors) : (vector_end - i) / kLanes;
    for (const int chunk_end = i + vectors * kLanes; i < chunk_end; i += kLanes) {
      flag_vector<kCount>(on, off, flags, i, limit, noise, noise_above, every_lane, any, loud_up, loud_down);
    }
    if constexpr (kCount) count_vectors<Pixel>(vectors, *lanes, *strobe, loud_up, loud_down);
  }
  // The rest of a row at least one vector wide: its last kLanes pixels, the overlap flagged again
  // (the same flags) and counted once.
  if (i < n && n >= kLanes) {
    const V keep = wide::last_lanes<V>(n - i);
    flag_vector<kCount>(on, off, flags, n - kLanes, limit, noise, noise_above, keep, any, loud_up, loud_down);
    if constexpr (kCount) count_vectors<Pixel>(1, *lanes, *strobe, loud_up, loud_down);
    i = n;
  }
  if constexpr (kCount) {
    wide::store(lanes->brighter_on, loud_up);
    wide::store(lanes->brighter_off, loud_down);
  }
  // Read back as words: scalar loads are cheaper than extracting lanes from a vector register.
  std::uint64_t words[sizeof(V) / 8];
  std::memcpy(words, &any, sizeof words);
  std::uint64_t found = 0;
  for (const std::uint64_t word : words) found |= word;
  for (; i < n; ++i) {
    const Pixel up = static_cast<Pixel>(on[i] > off[i] ? on[i] - off[i] : 0);
    flags[i] = static_cast<Pixel>(up > threshold ? up - threshold : 0);
    found |= flags[i];
    if constexpr (kCount) {
      const Pixel down = static_cast<Pixel>(off[i] > on[i] ? off[i] - on[i] : 0);
      strobe->brighter_on += up > noise_level ? 1u : 0u;
      strobe->brighter_off += down > noise_level ? 1u : 0u;
    }
  }
  return found != 0;
}

// The pass at each width the CPU can run (wide_vectors.hpp): the baseline build (SSE2, NEON) uses
// 32-byte vectors too, two registers per operation. A row with a flag set then has its full blocks'
// bits formed from the flags, which the pass just left in the first-level cache.
template <typename Pixel, bool kCount>
struct FlagRow {
  IRLOC_WIDE_KERNEL_16 static bool run(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel noise_level,
                                       Pixel* flags, std::uint64_t* bits, StrobeLaneCounts* lanes,
                                       StrobeCounts* strobe) {
    const bool any = flag_row<32, Pixel, kCount>(on, off, n, threshold, noise_level, flags, lanes, strobe);
    if (any) block_bits_packed(flags, n / 64, bits);
    return any;
  }
  IRLOC_WIDE_KERNEL_32(static bool run(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel noise_level,
                                       Pixel* flags, std::uint64_t* bits, StrobeLaneCounts* lanes,
                                       StrobeCounts* strobe) {
    const bool any = flag_row<32, Pixel, kCount>(on, off, n, threshold, noise_level, flags, lanes, strobe);
    if (any) block_bits_avx2(flags, n / 64, bits);
    return any;
  })
  IRLOC_WIDE_KERNEL_64(static bool run(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel noise_level,
                                       Pixel* flags, std::uint64_t* bits, StrobeLaneCounts* lanes,
                                       StrobeCounts* strobe) {
    const bool any = flag_row<64, Pixel, kCount>(on, off, n, threshold, noise_level, flags, lanes, strobe);
    if (any) block_bits_avx512(flags, n / 64, bits);
    return any;
  })
};

}  // namespace

bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t* flags, std::uint64_t* bits) {
  return FlagRow<std::uint8_t, false>::run(on, off, n, threshold, 0, flags, bits, nullptr, nullptr);
}

bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t* flags, std::uint64_t* bits) {
  return FlagRow<std::uint16_t, false>::run(on, off, n, threshold, 0, flags, bits, nullptr, nullptr);
}

bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n, std::uint8_t threshold,
                           std::uint8_t noise_level, std::uint8_t* flags, std::uint64_t* bits, StrobeLaneCounts& lanes,
                           StrobeCounts& strobe) {
  return FlagRow<std::uint8_t, true>::run(on, off, n, threshold, noise_level, flags, bits, &lanes, &strobe);
}

bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n, std::uint16_t threshold,
                           std::uint16_t noise_level, std::uint16_t* flags, std::uint64_t* bits,
                           StrobeLaneCounts& lanes, StrobeCounts& strobe) {
  return FlagRow<std::uint16_t, true>::run(on, off, n, threshold, noise_level, flags, bits, &lanes, &strobe);
}

}  // namespace irloc::detail
