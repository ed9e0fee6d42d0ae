#pragma once
// Row primitives over 16-byte GCC vectors: SSE2 on x86-64, NEON on aarch64, from one source.
// Internal to algo/kernels; every function reads/writes exactly n pixels and accepts any
// alignment (vectors are loaded with memcpy).

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace irloc::simd {

template <typename Pixel>
struct VectorOf;
template <>
struct VectorOf<std::uint8_t> {
  typedef std::uint8_t type __attribute__((vector_size(16)));
};
template <>
struct VectorOf<std::uint16_t> {
  typedef std::uint16_t type __attribute__((vector_size(16)));
};
template <typename Pixel>
using Vec = typename VectorOf<Pixel>::type;

template <typename Pixel>
inline constexpr int kLanes = 16 / static_cast<int>(sizeof(Pixel));

template <typename Pixel>
inline Vec<Pixel> load(const Pixel* p) {
  Vec<Pixel> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <typename Pixel>
inline void store(Pixel* p, Vec<Pixel> v) {
  std::memcpy(p, &v, sizeof v);
}

// max(a - b, 0) lane by lane, as a - min(a, b): no wrap-around for unsigned pixels.
template <typename V>
inline V vector_saturating_subtract(V a, V b) {
  return a - (a < b ? a : b);
}

template <typename Pixel>
inline Pixel saturating_subtract(Pixel a, Pixel b) {
  return static_cast<Pixel>(a > b ? a - b : 0);
}

template <typename V>
inline V vector_max(V a, V b) {
  return a > b ? a : b;
}

template <typename V>
inline V vector_min(V a, V b) {
  return a < b ? a : b;
}

template <typename Pixel>
inline Pixel horizontal_max(Vec<Pixel> v) {
  Pixel m = 0;
  for (int k = 0; k < kLanes<Pixel>; ++k) m = std::max(m, static_cast<Pixel>(v[k]));
  return m;
}

// Whether any lane is nonzero: the vector as two 64-bit words, no lane-by-lane reduction.
template <typename V>
inline bool any_nonzero(V v) {
  static_assert(sizeof(V) == 16);
  std::uint64_t words[2];
  std::memcpy(words, &v, sizeof words);
  return (words[0] | words[1]) != 0;
}

// The largest pixel of a row: the zero-row test when extracting runs from a binary image.
template <typename Pixel>
inline Pixel max_value(const Pixel* row, int n) {
  constexpr int lanes = kLanes<Pixel>;
  Vec<Pixel> m0 = {};
  Vec<Pixel> m1 = {};
  int i = 0;
  for (; i + 2 * lanes <= n; i += 2 * lanes) {
    m0 = vector_max(m0, load(row + i));
    m1 = vector_max(m1, load(row + i + lanes));
  }
  Pixel m = horizontal_max<Pixel>(vector_max(m0, m1));
  for (; i < n; ++i) m = std::max(m, row[i]);
  return m;
}

// flags[i] = max(on[i] - off[i] - threshold, 0), nonzero exactly where the difference is above
// the threshold, for i < n; returns whether any flag is set. The fused path's single pass over a
// row of the frame pair: on > off + threshold is tested as on - min(on, min(off, max - t) + t),
// four lane operations with no overflow and no unsigned compare (which SSE2 lacks).
template <typename Pixel>
inline bool flag_difference_above(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel* flags) {
  using V = Vec<Pixel>;
  constexpr int lanes = kLanes<Pixel>;
  const V limit = V{} + threshold;
  const V headroom = V{} + static_cast<Pixel>(static_cast<Pixel>(~Pixel{0}) - threshold);
  const auto flag = [&](int i) {
    const V raised = vector_min(load(off + i), headroom) + limit;  // min(off + t, max)
    return vector_saturating_subtract(load(on + i), raised);
  };
  V any0 = {};
  V any1 = {};
  int i = 0;
  for (; i + 2 * lanes <= n; i += 2 * lanes) {
    const V f0 = flag(i);
    const V f1 = flag(i + lanes);
    store(flags + i, f0);
    store(flags + i + lanes, f1);
    any0 |= f0;
    any1 |= f1;
  }
  for (; i + lanes <= n; i += lanes) {
    const V f0 = flag(i);
    store(flags + i, f0);
    any0 |= f0;
  }
  bool found = any_nonzero(any0 | any1);
  for (; i < n; ++i) {
    const Pixel difference = saturating_subtract(on[i], off[i]);
    flags[i] = saturating_subtract(difference, threshold);
    found = found || flags[i] != 0;
  }
  return found;
}

}  // namespace irloc::simd
