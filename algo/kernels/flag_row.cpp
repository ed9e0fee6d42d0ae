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
// The chunk summary costs a few register operations per 32 bytes in a loop bound by loading the
// frames, and saves the run scan from testing the flags of dark chunks again.
template <typename Pixel>
inline bool flag_row(const Pixel* on, const Pixel* off, int n, Pixel threshold, Pixel* flags, std::uint8_t* chunks) {
  using V = typename Wide<Pixel>::type;
  constexpr int lanes = static_cast<int>(sizeof(V) / sizeof(Pixel));
  static_assert(lanes == kPixelsPerChunk<Pixel>);
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
    std::uint64_t words[sizeof(V) / 8];
    std::memcpy(words, &flag, sizeof words);
    chunks[i / lanes] = (words[0] | words[1] | words[2] | words[3]) != 0;
    any |= flag;
  }
  std::uint64_t words[sizeof(V) / 8];
  std::memcpy(words, &any, sizeof words);
  std::uint64_t found = 0;
  for (const std::uint64_t word : words) found |= word;
  if (i < n) {
    std::uint64_t tail = 0;
    for (int k = i; k < n; ++k) {
      const Pixel difference = static_cast<Pixel>(on[k] > off[k] ? on[k] - off[k] : 0);
      flags[k] = static_cast<Pixel>(difference > threshold ? difference - threshold : 0);
      tail |= flags[k];
    }
    chunks[i / lanes] = tail != 0;
    found |= tail;
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
                                               std::uint8_t threshold, std::uint8_t* flags, std::uint8_t* chunks) {
  return flag_row(on, off, n, threshold, flags, chunks);
}

IRLOC_VECTOR_CLONES bool flag_difference_above(const std::uint16_t* on, const std::uint16_t* off, int n,
                                               std::uint16_t threshold, std::uint16_t* flags,
                                               std::uint8_t* chunks) {
  return flag_row(on, off, n, threshold, flags, chunks);
}

}  // namespace irloc::detail
