#include "algo/kernels/flag_row.hpp"

#include <cstring>

namespace irloc::detail {
namespace {

// 32-byte GCC vectors: one AVX2 register, or two SSE2 / NEON registers (the compiler splits them).
template <typename Pixel>
struct Wide;
template <>
struct Wide<std::uint8_t> {
  typedef std::uint8_t type __attribute__((vector_size(32)));
};
template <>
struct Wide<std::uint16_t> {
  typedef std::uint16_t type __attribute__((vector_size(32)));
};

// on > off + threshold is tested as on - min(on, min(off, max - threshold) + threshold): four lane
// operations, no overflow and no unsigned compare (which SSE2 lacks). Vectors stay local to this
// function (none is passed by value), so its code does not depend on the vector calling convention.
template <typename Pixel>
inline bool flag_row(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel* flags) {
  using V = typename Wide<Pixel>::type;
  constexpr int lanes = static_cast<int>(sizeof(V) / sizeof(Pixel));
  const V limit = V{} + threshold;
  const V headroom = V{} + static_cast<Pixel>(static_cast<Pixel>(~Pixel{0}) - threshold);
  V any = {};
  int i = 0;
  for (; i + lanes <= n; i += lanes) {
    V a;
    V b;
    std::memcpy(&a, on + i, sizeof a);
    std::memcpy(&b, off + i, sizeof b);
    const V raised = (b < headroom ? b : headroom) + limit;  // min(off + t, max)
    const V flag = a - (a < raised ? a : raised);
    std::memcpy(flags + i, &flag, sizeof flag);
    // Read back as words: scalar loads are cheaper than extracting lanes from a vector register.
    any |= flag;
  }
  std::uint64_t words[sizeof(V) / 8];
  std::memcpy(words, &any, sizeof words);
  std::uint64_t found = 0;
  for (const std::uint64_t word : words) found |= word;
  for (; i < n; ++i) {
    const Pixel difference = static_cast<Pixel>(on[i] > off[i] ? on[i] - off[i] : 0);
    flags[i] = static_cast<Pixel>(difference > threshold ? difference - threshold : 0);
    found |= flags[i];
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
  return flag_row(on, off, n, threshold, flags);
}

IRLOC_VECTOR_CLONES bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n,
                                               std::uint16_t threshold, std::uint16_t* flags) {
  return flag_row(on, off, n, threshold, flags);
}

}  // namespace irloc::detail
