#pragma once
// The row scans shared by the run extractors. Internal to algo/kernels.
//
// A row's full 64-pixel blocks are scanned as 64-bit words of bits, one a pixel: either as the row
// pass formed them in vector registers (flag_row.hpp), or packed from its flags, read as 64-bit
// words (8 8-bit or 4 16-bit flags): a block of 64 flags that holds a nonzero one is packed to 64
// bits without a branch (pack_flag_word). In the bits, runs are found with bit operations
// (count-trailing-zeros finds the next start or end), so the cost is per run, not per pixel or
// word, and nearly branch-free. Little-endian targets only (x86-64, aarch64): lane k of a word is
// its k-th least significant lane.

#include <bit>
#include <cstdint>
#include <cstring>

namespace irloc::detail {

static_assert(std::endian::native == std::endian::little, "run scans read flag lanes in little-endian order");

// Tracks the open run across words and reports finished ones.
template <typename AddRun>
class RunTracker {
 public:
  explicit RunTracker(const AddRun& add_run) : add_run_(add_run) {}

  // A stretch of flags that are all zero starts at x.
  void dark_at(int x) {
    if (run_start_ >= 0) {
      add_run_(run_start_, x);
      run_start_ = -1;
    }
  }

  // The word of kBits-bit lanes whose first pixel is x: flags (8 or 16 bits, a pixel's lane
  // nonzero where it is set) or packed bits (1). Out of line: the scan's loop over a row's blocks,
  // most of them dark, then keeps its values in registers (inlined with the run handler's
  // union-find, it kept them on the stack: 8 % of the 1280x960 front end).
  template <int kBits>
  __attribute__((noinline)) void word(std::uint64_t flags, int x) {
    constexpr int kLanes = 64 / kBits;
    constexpr std::uint64_t kLow = ~std::uint64_t{0} / ((std::uint64_t{1} << kBits) - 1) * ((std::uint64_t{1} << (kBits - 1)) - 1);
    constexpr std::uint64_t kTop = ~kLow;  // the top bit of every lane
    // Top bit of each lane set iff the lane is nonzero.
    std::uint64_t set = (((flags & kLow) + kLow) | flags) & kTop;
    const std::uint64_t clear = ~set & kTop;
    int lane = 0;
    if (run_start_ >= 0) {  // a run continues from the previous word
      if (clear == 0) {
        set_pixels_ += kLanes;
        return;
      }
      lane = std::countr_zero(clear) / kBits;
      add_run_(run_start_, x + lane);
      set_pixels_ += static_cast<std::uint32_t>(lane);
      run_start_ = -1;
      set &= ~std::uint64_t{0} << (lane * kBits);
    }
    while (set != 0) {
      const int start = std::countr_zero(set) / kBits;
      const std::uint64_t clear_after = clear & (~std::uint64_t{0} << (start * kBits));
      if (clear_after == 0) {  // runs on into the next word
        run_start_ = x + start;
        set_pixels_ += static_cast<std::uint32_t>(kLanes - start);
        return;
      }
      const int end = std::countr_zero(clear_after) / kBits;
      add_run_(x + start, x + end);
      set_pixels_ += static_cast<std::uint32_t>(end - start);
      set &= ~std::uint64_t{0} << (end * kBits);  // end < kLanes here, so the shift is < 64
    }
  }

  // A single flag at x (the row's tail, shorter than a word).
  template <typename Lane>
  void pixel(Lane flag, int x) {
    if (flag != 0) {
      ++set_pixels_;
      if (run_start_ < 0) run_start_ = x;
    } else {
      dark_at(x);
    }
  }

  // Closes the open run at the row's end; returns the number of set flags.
  std::uint32_t finish(int width) {
    dark_at(width);
    return set_pixels_;
  }

 private:
  const AddRun& add_run_;
  int run_start_ = -1;
  std::uint32_t set_pixels_ = 0;
};

// The flags of one 64-bit word (8 8-bit or 4 16-bit lanes, zero or not) as bits, lane k to bit
// k. Each nonzero lane's top bit is set (as in RunTracker::word) and moved to the lane's bit 0;
// one multiplication then gathers lane k's bit into bit (64 - lanes + k): every partial product
// lands on a bit of its own, so nothing carries.
template <typename Flag>
inline std::uint64_t pack_flag_word(std::uint64_t flags) {
  constexpr int kBits = 8 * static_cast<int>(sizeof(Flag));
  constexpr int kLanes = 64 / kBits;
  constexpr std::uint64_t kLow = ~std::uint64_t{0} / ((std::uint64_t{1} << kBits) - 1) * ((std::uint64_t{1} << (kBits - 1)) - 1);
  constexpr std::uint64_t kTop = ~kLow;
  constexpr std::uint64_t kGather = kBits == 8 ? 0x0102040810204080ull
                                               : (1ull << 60) | (1ull << 45) | (1ull << 30) | (1ull << 15);
  const std::uint64_t set = ((((flags & kLow) + kLow) | flags) & kTop) >> (kBits - 1);
  return (set * kGather) >> (64 - kLanes);
}

// The 8 bytes of flags at p as one word.
template <typename Flag>
inline std::uint64_t load_word(const Flag* p) {
  std::uint64_t word;
  std::memcpy(&word, p, sizeof word);
  return word;
}

// The 64 flags at p as bits, flag k to bit k.
template <typename Flag>
inline std::uint64_t pack_flag_block(const Flag* p) {
  constexpr int kPerWord = static_cast<int>(8 / sizeof(Flag));
  std::uint64_t bits = 0;
  for (int w = 0; w < 64 / kPerWord; ++w) bits |= pack_flag_word<Flag>(load_word(p + w * kPerWord)) << (w * kPerWord);
  return bits;
}

// The 64 flags at p as bits, flag k to bit k. A block of zero flags costs its word loads and one
// test: on a noisy ceiling most rows hold a few foreground pixels, and most of such a row is still
// dark. The loads come straight from the row: a copy of the block into an array would go through
// the stack (stores that the word loads then wait on).
template <typename Flag>
inline std::uint64_t flag_block_bits(const Flag* p) {
  constexpr int kPerWord = static_cast<int>(8 / sizeof(Flag));
  std::uint64_t any = 0;
  for (int w = 0; w < 64 / kPerWord; ++w) any |= load_word(p + w * kPerWord);
  return any == 0 ? 0 : pack_flag_block(p);
}

// Calls add_run(x_begin, x_end) for every maximal run of set pixels x in [0, width), and returns
// how many were set: the row's full 64-pixel blocks given as bits by block_bits(b) (pixel 64 b + k
// at bit k), the rest as the nonzero ones of flags[x].
template <typename Flag, typename BlockBits, typename AddRun>
inline std::uint32_t scan_blocks_and_rest(const BlockBits& block_bits, const Flag* flags, int width,
                                          const AddRun& add_run) {
  constexpr int kPerWord = static_cast<int>(8 / sizeof(Flag));
  constexpr int kLaneBits = 8 * static_cast<int>(sizeof(Flag));
  RunTracker tracker(add_run);
  int x = 0;
  for (; x + 64 <= width; x += 64) {
    const std::uint64_t bits = block_bits(x / 64);
    if (bits == 0) tracker.dark_at(x);
    else tracker.template word<1>(bits, x);
  }
  for (; x + kPerWord <= width; x += kPerWord) {
    const std::uint64_t word = load_word(flags + x);
    if (word == 0) tracker.dark_at(x);
    else tracker.template word<kLaneBits>(word, x);
  }
  for (; x < width; ++x) tracker.pixel(flags[x], x);
  return tracker.finish(width);
}

// The runs of nonzero flags[x], x in [0, width), as above.
template <typename Flag, typename AddRun>
inline std::uint32_t scan_runs(const Flag* flags, int width, const AddRun& add_run) {
  return scan_blocks_and_rest([flags](int block) { return flag_block_bits(flags + 64 * block); }, flags, width,
                              add_run);
}

// The same, the full blocks read from bits (bits[b] as flag_block_bits(flags + 64 b) would give
// it, b < width / 64), as the row pass forms them (flag_row.hpp).
template <typename Flag, typename AddRun>
inline std::uint32_t scan_runs(const std::uint64_t* bits, const Flag* flags, int width, const AddRun& add_run) {
  return scan_blocks_and_rest([bits](int block) { return bits[block]; }, flags, width, add_run);
}

}  // namespace irloc::detail
