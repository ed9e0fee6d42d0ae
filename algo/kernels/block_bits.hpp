#pragma once
// A row's flags as bits, a 64-bit word per full 64-pixel block (bits[b] bit k set iff flags[64 b +
// k] != 0), for the run scans (run_scan.hpp). Internal to algo/kernels. Where an instruction set
// forms a vector's nonzero lanes as bits directly (AVX-512BW tests into a mask register, AVX2
// compares with zero and gathers the bytes' top bits), its version of a kernel (wide_vectors.hpp)
// calls the helper for it; each helper carries a target that its kernel version's includes, and
// must be called from that version itself (GCC inlines a target's helper only into a function of
// that target, not through a plain always_inline one). Elsewhere (SSE2, NEON) the flags are
// packed as 64-bit words (run_scan.hpp).

#include <cstdint>
#include <cstring>

#include "algo/kernels/run_scan.hpp"
#include "algo/kernels/wide_vectors.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace irloc::detail {

template <typename Flag>
inline void block_bits_packed(const Flag* flags, int blocks, std::uint64_t* bits) {
  for (int b = 0; b < blocks; ++b) bits[b] = flag_block_bits(flags + 64 * b);
}

#if defined(__x86_64__)

// The 32 bytes at p: bit k set iff byte k is nonzero.
__attribute__((target("avx2"), always_inline)) inline std::uint64_t nonzero_bytes_avx2(const void* p) {
  const __m256i bytes = _mm256_loadu_si256(static_cast<const __m256i*>(p));
  const __m256i zero = _mm256_cmpeq_epi8(bytes, _mm256_setzero_si256());
  return ~static_cast<std::uint32_t>(_mm256_movemask_epi8(zero));
}

// The 16 16-bit lanes at p: bit k set iff lane k is nonzero. Their zero masks packed to bytes
// hold, in each 128-bit half, that half's 8 lanes twice.
__attribute__((target("avx2"), always_inline)) inline std::uint64_t nonzero_lanes16_avx2(const void* p) {
  const __m256i lanes = _mm256_loadu_si256(static_cast<const __m256i*>(p));
  const __m256i zero = _mm256_cmpeq_epi16(lanes, _mm256_setzero_si256());
  const auto mask = static_cast<std::uint32_t>(_mm256_movemask_epi8(_mm256_packs_epi16(zero, zero)));
  return ~((mask & 0xffu) | ((mask >> 8) & 0xff00u)) & 0xffffu;
}

__attribute__((target("avx2"), always_inline)) inline void block_bits_avx2(const std::uint8_t* flags, int blocks,
                                                                          std::uint64_t* bits) {
  for (int b = 0; b < blocks; ++b) {
    bits[b] = nonzero_bytes_avx2(flags + 64 * b) | nonzero_bytes_avx2(flags + 64 * b + 32) << 32;
  }
}

__attribute__((target("avx2"), always_inline)) inline void block_bits_avx2(const std::uint16_t* flags, int blocks,
                                                                          std::uint64_t* bits) {
  for (int b = 0; b < blocks; ++b) {
    const std::uint16_t* block = flags + 64 * b;
    bits[b] = nonzero_lanes16_avx2(block) | nonzero_lanes16_avx2(block + 16) << 16 |
              nonzero_lanes16_avx2(block + 32) << 32 | nonzero_lanes16_avx2(block + 48) << 48;
  }
}

__attribute__((target("avx512bw"), always_inline)) inline void block_bits_avx512(const std::uint8_t* flags,
                                                                                int blocks, std::uint64_t* bits) {
  for (int b = 0; b < blocks; ++b) {
    const __m512i block = _mm512_loadu_si512(flags + 64 * b);
    bits[b] = _mm512_test_epi8_mask(block, block);
  }
}

__attribute__((target("avx512bw"), always_inline)) inline void block_bits_avx512(const std::uint16_t* flags,
                                                                                int blocks, std::uint64_t* bits) {
  for (int b = 0; b < blocks; ++b) {
    const __m512i low = _mm512_loadu_si512(flags + 64 * b);
    const __m512i high = _mm512_loadu_si512(flags + 64 * b + 32);
    bits[b] = _mm512_test_epi16_mask(low, low) | static_cast<std::uint64_t>(_mm512_test_epi16_mask(high, high)) << 32;
  }
}

#endif

}  // namespace irloc::detail
