#include "algo/kernels/flag_row.hpp"

#include <algorithm>
#include <cstring>
#include <limits>

namespace irloc::detail {
namespace {

// GCC vectors of 32 bytes: one AVX2 register, or two SSE2 / NEON registers. The compiler splits
// lane arithmetic and min natively, but would lower a comparison lane by lane (only 16-byte vectors
// compare natively on SSE2 and NEON), so the pass uses none.
template <typename Pixel>
struct Vector {
  typedef Pixel type __attribute__((vector_size(32)));
};

// The sum of a vector's lanes. Lanes are read by subscript: taking the vector's address would keep
// the counters in memory throughout the loop that fills them.
template <typename V>
std::uint64_t lane_sum(const V& lanes) {
  std::uint64_t sum = 0;
  for (std::size_t k = 0; k < sizeof(V) / sizeof(lanes[0]); ++k) sum += lanes[k];
  return sum;
}

// With m = min(on, off): up = on - m = max(on - off, 0), down = off - m = max(off - on, 0), and
// the flag up - min(up, threshold) = max(on - off - threshold, 0): four lane operations, no
// overflow and no unsigned compare (which SSE2 lacks). With kCount, the lanes where up (down) is
// above the noise level n are counted without a comparison either: min(up, n + 1) - min(up, n) is
// 1 exactly there (0 throughout when n is the largest value, which no difference exceeds), added
// to lane counters that are emptied before they can wrap. So every operation is lane arithmetic
// or min, which one AVX2 register or two SSE2 / NEON registers do natively. (A min against the
// constant 1 would not do: the compiler turns it into a comparison with 0.) Vectors stay local
// to this function (none is passed by value), so its code does not depend on the vector calling
// convention.
template <typename Pixel, bool kCount>
__attribute__((always_inline)) inline bool flag_row(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel noise_level, Pixel* flags,
                     StrobeCounts* strobe) {
  using V = typename Vector<Pixel>::type;
  constexpr int lanes = static_cast<int>(sizeof(V) / sizeof(Pixel));
  constexpr int kMaxChunk = std::numeric_limits<Pixel>::max();  // vectors before a lane counter could wrap
  const V limit = V{} + threshold;
  const V noise = V{} + noise_level;
  const Pixel above_noise = noise_level == std::numeric_limits<Pixel>::max() ? noise_level : static_cast<Pixel>(noise_level + 1);
  const V noise_above = V{} + above_noise;
  V any = {};
  int i = 0;
  const int vector_end = n - n % lanes;
  while (i < vector_end) {
    const int chunk_end = i + std::min(vector_end - i, kMaxChunk * lanes);
    V loud_up_lanes = {};
    V loud_down_lanes = {};
    for (; i < chunk_end; i += lanes) {
      V a;
      V b;
      std::memcpy(&a, on + i, sizeof a);
      std::memcpy(&b, off + i, sizeof b);
      const V low = a < b ? a : b;
      const V up = a - low;
      const V flag = up - (up < limit ? up : limit);
      std::memcpy(flags + i, &flag, sizeof flag);
      any |= flag;
      if constexpr (kCount) {
        const V down = b - low;
        loud_up_lanes += (up < noise_above ? up : noise_above) - (up < noise ? up : noise);
        loud_down_lanes += (down < noise_above ? down : noise_above) - (down < noise ? down : noise);
      }
    }
    if constexpr (kCount) {
      strobe->brighter_on += lane_sum(loud_up_lanes);
      strobe->brighter_off += lane_sum(loud_down_lanes);
    }
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

}  // namespace

// On x86-64 the baseline (SSE2) and an AVX2 clone are built and the loader picks by CPU; other
// targets build the one baseline version (NEON on aarch64).
#if defined(__x86_64__)
#define IRLOC_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define IRLOC_VECTOR_CLONES
#endif

IRLOC_VECTOR_CLONES bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n,
                                               std::uint8_t threshold, std::uint8_t* flags) {
  return flag_row<std::uint8_t, false>(on, off, n, threshold, 0, flags, nullptr);
}

IRLOC_VECTOR_CLONES bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n,
                                               std::uint16_t threshold, std::uint16_t* flags) {
  return flag_row<std::uint16_t, false>(on, off, n, threshold, 0, flags, nullptr);
}

IRLOC_VECTOR_CLONES bool flag_difference_above(const std::uint8_t* on, const std::uint8_t* off, int n,
                                               std::uint8_t threshold, std::uint8_t noise_level, std::uint8_t* flags,
                                               StrobeCounts& strobe) {
  return flag_row<std::uint8_t, true>(on, off, n, threshold, noise_level, flags, &strobe);
}

IRLOC_VECTOR_CLONES bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n,
                                               std::uint16_t threshold, std::uint16_t noise_level, std::uint16_t* flags,
                                               StrobeCounts& strobe) {
  return flag_row<std::uint16_t, true>(on, off, n, threshold, noise_level, flags, &strobe);
}

}  // namespace irloc::detail
