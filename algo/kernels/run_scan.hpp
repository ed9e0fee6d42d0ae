#pragma once
// The row scan shared by the run extractors. Internal to algo/kernels.

#include <cstdint>
#include <cstring>

namespace irloc::detail {

// Calls add_run(x_begin, x_end) for every maximal run of nonzero flags[x], x in [0, width), and
// returns how many flags were nonzero. Flags are read 32 bytes at a time (32 8-bit pixels, 16
// 16-bit ones): an all-zero chunk costs four loads and one test; otherwise its 8-byte words are
// tested in turn and only nonzero words are walked pixel by pixel.
template <typename Flag, typename AddRun>
inline std::uint32_t scan_runs(const Flag* flags, int width, const AddRun& add_run) {
  constexpr int kPerWord = static_cast<int>(8 / sizeof(Flag));
  std::uint32_t set = 0;
  int run_start = -1;
  int x = 0;
  const auto visit = [&](int at) {
    if (flags[at] != 0) {
      ++set;
      if (run_start < 0) run_start = at;
    } else if (run_start >= 0) {
      add_run(run_start, at);
      run_start = -1;
    }
  };
  const auto close_run = [&](int at) {
    if (run_start >= 0) {
      add_run(run_start, at);
      run_start = -1;
    }
  };
  for (; x + 4 * kPerWord <= width; x += 4 * kPerWord) {
    std::uint64_t words[4];
    std::memcpy(words, flags + x, sizeof words);
    if ((words[0] | words[1] | words[2] | words[3]) == 0) {
      close_run(x);
      continue;
    }
    for (int w = 0; w < 4; ++w) {
      const int word_x = x + w * kPerWord;
      if (words[w] == 0) {
        close_run(word_x);
        continue;
      }
      for (int k = 0; k < kPerWord; ++k) visit(word_x + k);
    }
  }
  for (; x < width; ++x) visit(x);
  if (run_start >= 0) add_run(run_start, width);
  return set;
}

}  // namespace irloc::detail
