#pragma once
// The row scan shared by the run extractors: skip blocks with nothing set, walk the rest pixel by
// pixel. Internal to algo/kernels.

#include <algorithm>
#include <cstdint>

namespace irloc::detail {

// Calls add_run(x_begin, x_end) for every maximal run of x in [0, width) with is_set(x) and
// returns how many pixels were set. A block of up to kBlock pixels [x, x + n) for which
// block_any(x, n) is false is passed over whole (block_any is a vector test; is_set is not).
template <int kBlock, typename BlockAny, typename IsSet, typename AddRun>
inline std::uint32_t scan_row(int width, const BlockAny& block_any, const IsSet& is_set, const AddRun& add_run) {
  std::uint32_t set_pixels = 0;
  int run_start = -1;
  int x = 0;
  while (x < width) {
    const int n = std::min(kBlock, width - x);
    if (!block_any(x, n)) {
      if (run_start >= 0) {
        add_run(run_start, x);
        run_start = -1;
      }
      x += n;
      continue;
    }
    for (const int block_end = x + n; x < block_end; ++x) {
      if (is_set(x)) {
        ++set_pixels;
        if (run_start < 0) run_start = x;
      } else if (run_start >= 0) {
        add_run(run_start, x);
        run_start = -1;
      }
    }
  }
  if (run_start >= 0) add_run(run_start, width);
  return set_pixels;
}

}  // namespace irloc::detail
