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

// Whether any lane of a 16-byte vector is nonzero (read back as two words: cheaper than lanes).
template <typename V>
inline bool any_lane(V v) {
  static_assert(sizeof(V) == 16);
  std::uint64_t words[2];
  std::memcpy(words, &v, sizeof words);
  return (words[0] | words[1]) != 0;
}

template <typename Pixel>
inline Pixel horizontal_max(Vec<Pixel> v) {
  Pixel m = 0;
  for (int k = 0; k < kLanes<Pixel>; ++k) m = std::max(m, static_cast<Pixel>(v[k]));
  return m;
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

}  // namespace irloc::simd
