#pragma once
// The row scans shared by the run extractors. Internal to algo/kernels.
//
// Flags are read as 64-bit words (8 8-bit or 4 16-bit flags). Inside a word, runs are found with
// bit operations (a lane's top bit marks a nonzero flag; count-trailing-zeros finds the next
// start or end), so the cost is per run, not per pixel, and nearly branch-free. Little-endian
// targets only (x86-64, aarch64): lane k of a word is its k-th least significant lane.

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

  // The word of lane-sized flags whose first pixel is x; Lane is the flag type.
  template <typename Lane>
  void word(std::uint64_t flags, int x) {
    constexpr int kBits = 8 * static_cast<int>(sizeof(Lane));
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

// The 8 bytes of flags at p as one word.
template <typename Flag>
inline std::uint64_t load_word(const Flag* p) {
  std::uint64_t word;
  std::memcpy(&word, p, sizeof word);
  return word;
}

// Calls add_run(x_begin, x_end) for every maximal run of nonzero flags[x], x in [0, width), and
// returns how many flags were nonzero.
template <typename Flag, typename AddRun>
inline std::uint32_t scan_runs(const Flag* flags, int width, const AddRun& add_run) {
  constexpr int kPerWord = static_cast<int>(8 / sizeof(Flag));
  // 64 dark bytes cost eight loads and one test: on a noisy ceiling most rows hold a few
  // foreground pixels, and most of such a row is still dark.
  constexpr int kWordsPerTest = 8;
  RunTracker tracker(add_run);
  int x = 0;
  const auto visit = [&](std::uint64_t word, int at) {
    if (word == 0) tracker.dark_at(at);
    else tracker.template word<Flag>(word, at);
  };
  for (; x + kWordsPerTest * kPerWord <= width; x += kWordsPerTest * kPerWord) {
    // Word loads straight from the row: a copy of the block into an array would go through the
    // stack (16-byte stores that the word loads then wait on).
    std::uint64_t any = 0;
    for (int w = 0; w < kWordsPerTest; ++w) any |= load_word(flags + x + w * kPerWord);
    if (any == 0) {
      tracker.dark_at(x);
      continue;
    }
    for (int w = 0; w < kWordsPerTest; ++w) visit(load_word(flags + x + w * kPerWord), x + w * kPerWord);
  }
  for (; x + kPerWord <= width; x += kPerWord) visit(load_word(flags + x), x);
  for (; x < width; ++x) tracker.pixel(flags[x], x);
  return tracker.finish(width);
}

}  // namespace irloc::detail
