#include "algo/kernels/square_mask_filter.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>

#include "algo/kernels/wide_vectors.hpp"

namespace irloc {
namespace {

using wide::load;
using wide::store;

// counts[x] += 1 where row[x] is counted (entering the window) or -= 1 (leaving it), in wrapping
// byte arithmetic: a counted pixel's indicator byte is 255, i.e. -1. The indicator is the pixel
// for dilation (set pixels count), its complement for erosion (clear pixels count).
template <int kBytes, bool kEnter>
__attribute__((always_inline)) inline void count_row(std::uint8_t* counts, const std::uint8_t* row, int n,
                                                     std::uint8_t flip) {
  using V = wide::Vec<std::uint8_t, kBytes>;
  const V flip_lanes = V{} + flip;
  int x = 0;
  for (; x + kBytes <= n; x += kBytes) {
    const V indicator = load<V>(row + x) ^ flip_lanes;
    const V count = load<V>(counts + x);
    store(counts + x, kEnter ? count - indicator : count + indicator);
  }
  for (; x < n; ++x) {
    const auto indicator = static_cast<std::uint8_t>(row[x] ^ flip);
    counts[x] = static_cast<std::uint8_t>(kEnter ? counts[x] - indicator : counts[x] + indicator);
  }
}

// counts[x] += 1 where entering[x] is counted and -= 1 where leaving[x] is (count_row's arithmetic),
// one read and write of the counts for the row that enters the window and the one that leaves it.
template <int kBytes>
__attribute__((always_inline)) inline void count_rows(std::uint8_t* counts, const std::uint8_t* entering,
                                                      const std::uint8_t* leaving, int n, std::uint8_t flip) {
  using V = wide::Vec<std::uint8_t, kBytes>;
  const V flip_lanes = V{} + flip;
  int x = 0;
  for (; x + kBytes <= n; x += kBytes) {
    const V enter = load<V>(entering + x) ^ flip_lanes;
    const V leave = load<V>(leaving + x) ^ flip_lanes;
    store(counts + x, load<V>(counts + x) - enter + leave);
  }
  for (; x < n; ++x) {
    const auto enter = static_cast<std::uint8_t>(entering[x] ^ flip), leave = static_cast<std::uint8_t>(leaving[x] ^ flip);
    counts[x] = static_cast<std::uint8_t>(counts[x] - enter + leave);
  }
}

// out[x] = 255 where counts[x] is 0 (no pixel of the window is counted), else 0; xor flip.
template <int kBytes>
__attribute__((always_inline)) inline void uncounted_row(const std::uint8_t* counts, int n, std::uint8_t flip,
                                                         std::uint8_t* out) {
  using V = wide::Vec<std::uint8_t, kBytes>;
  const V flip_lanes = V{} + flip;
  int x = 0;
  for (; x + kBytes <= n; x += kBytes) store(out + x, reinterpret_cast<V>(load<V>(counts + x) == 0) ^ flip_lanes);
  for (; x < n; ++x) out[x] = static_cast<std::uint8_t>((counts[x] == 0 ? 255 : 0) ^ flip);
}

// out[x] = min (kErode) or max of in[x - shift], in[x], in[x + shift] for x < n; in is padded by
// at least shift neutral bytes on both sides.
template <int kBytes, bool kErode>
__attribute__((always_inline)) inline void shift_step(const std::uint8_t* in, int n, int shift, std::uint8_t* out) {
  using V = wide::Vec<std::uint8_t, kBytes>;
  int x = 0;
  for (; x + kBytes <= n; x += kBytes) {
    const V left = load<V>(in + x - shift), middle = load<V>(in + x), right = load<V>(in + x + shift);
    if constexpr (kErode) {
      const V low = left < middle ? left : middle;
      store(out + x, low < right ? low : right);
    } else {
      const V high = left > middle ? left : middle;
      store(out + x, high > right ? high : right);
    }
  }
  for (; x < n; ++x) {
    out[x] = kErode ? std::min({in[x - shift], in[x], in[x + shift]}) : std::max({in[x - shift], in[x], in[x + shift]});
  }
}

IRLOC_WIDE_KERNEL_16 void enter_row(std::uint8_t* counts, const std::uint8_t* row, int n, std::uint8_t flip) {
  count_row<16, true>(counts, row, n, flip);
}
IRLOC_WIDE_KERNEL_32(void enter_row(std::uint8_t* counts, const std::uint8_t* row, int n, std::uint8_t flip) {
  count_row<32, true>(counts, row, n, flip);
})
IRLOC_WIDE_KERNEL_16 void leave_row(std::uint8_t* counts, const std::uint8_t* row, int n, std::uint8_t flip) {
  count_row<16, false>(counts, row, n, flip);
}
IRLOC_WIDE_KERNEL_32(void leave_row(std::uint8_t* counts, const std::uint8_t* row, int n, std::uint8_t flip) {
  count_row<32, false>(counts, row, n, flip);
})
IRLOC_WIDE_KERNEL_16 void enter_and_leave(std::uint8_t* counts, const std::uint8_t* entering,
                                          const std::uint8_t* leaving, int n, std::uint8_t flip) {
  count_rows<16>(counts, entering, leaving, n, flip);
}
IRLOC_WIDE_KERNEL_32(void enter_and_leave(std::uint8_t* counts, const std::uint8_t* entering,
                                          const std::uint8_t* leaving, int n, std::uint8_t flip) {
  count_rows<32>(counts, entering, leaving, n, flip);
})
IRLOC_WIDE_KERNEL_16 void window_mask(const std::uint8_t* counts, int n, std::uint8_t flip, std::uint8_t* out) {
  uncounted_row<16>(counts, n, flip, out);
}
IRLOC_WIDE_KERNEL_32(void window_mask(const std::uint8_t* counts, int n, std::uint8_t flip, std::uint8_t* out) {
  uncounted_row<32>(counts, n, flip, out);
})
IRLOC_WIDE_KERNEL_16 void erode_step(const std::uint8_t* in, int n, int shift, std::uint8_t* out) {
  shift_step<16, true>(in, n, shift, out);
}
IRLOC_WIDE_KERNEL_32(void erode_step(const std::uint8_t* in, int n, int shift, std::uint8_t* out) {
  shift_step<32, true>(in, n, shift, out);
})
IRLOC_WIDE_KERNEL_16 void dilate_step(const std::uint8_t* in, int n, int shift, std::uint8_t* out) {
  shift_step<16, false>(in, n, shift, out);
}
IRLOC_WIDE_KERNEL_32(void dilate_step(const std::uint8_t* in, int n, int shift, std::uint8_t* out) {
  shift_step<32, false>(in, n, shift, out);
})

}  // namespace

SquareMaskFilter::SquareMaskFilter(int max_width, int radius, Operation operation)
    : max_width_(std::max(max_width, 1)),
      radius_(radius),
      operation_(operation),
      neutral_(operation == Operation::erode ? 255 : 0),
      counts_(static_cast<std::size_t>(max_width_)),
      result_(static_cast<std::size_t>(max_width_)) {
  if (radius < 0 || radius > kMaxRadius) {
    throw std::invalid_argument("square mask filter: radius " + std::to_string(radius) + " outside 0.." +
                                std::to_string(kMaxRadius));
  }
  for (std::vector<std::uint8_t>& padded : padded_) padded.assign(static_cast<std::size_t>(max_width_ + 2 * radius), neutral_);
}

const std::uint8_t* SquareMaskFilter::row(ImageView8 in, int y) {
  filter_row(in, y, result_.data());
  return result_.data();
}

void SquareMaskFilter::apply(ImageView8 in, MutableImageView8 out) {
  assert(in.same_size(out.width(), out.height()));
  for (int y = 0; y < in.height(); ++y) filter_row(in, y, out.row(y));
}

void SquareMaskFilter::skip_row(ImageView8 in, int y) { count_window(in, y); }

void SquareMaskFilter::count_window(ImageView8 in, int y) {
  const int width = in.width(), height = in.height(), r = radius_;
  assert(width <= max_width_ && y >= 0 && y < height);
  const std::uint8_t flip = counted_flip();
  if (y == 0) {
    std::fill_n(counts_.begin(), width, std::uint8_t{0});
    rows_counted_ = 0;
  }
  const int last_entering = std::min(y + r, height - 1);
  const bool one_leaves = y - r - 1 >= 0;
  // Within the image one row enters and one leaves: both in one pass over the counts.
  if (one_leaves && rows_counted_ == last_entering) {
    enter_and_leave(counts_.data(), in.row(rows_counted_++), in.row(y - r - 1), width, flip);
    return;
  }
  for (; rows_counted_ <= last_entering; ++rows_counted_) enter_row(counts_.data(), in.row(rows_counted_), width, flip);
  if (one_leaves) leave_row(counts_.data(), in.row(y - r - 1), width, flip);
}

void SquareMaskFilter::filter_row(ImageView8 in, int y, std::uint8_t* out) {
  count_window(in, y);
  const int width = in.width(), r = radius_;
  const std::uint8_t flip = counted_flip();
  // The column's window is 255 where no pixel of it is counted; flipped back for erosion, where
  // the counted pixels are the clear ones.
  std::uint8_t* column = r == 0 ? out : padded_[0].data() + r;
  window_mask(counts_.data(), width, static_cast<std::uint8_t>(~flip), column);
  if (r == 0) return;
  // Outside the row the column mask is neutral (pixels outside the image are ignored); a step
  // that leaves r - reach to go is computed over the row and r - reach beyond each end, which the
  // next steps read (near the ends a window reaches outside the image).
  std::fill_n(padded_[0].begin(), r, neutral_);
  std::fill_n(padded_[0].begin() + r + width, r, neutral_);
  int reach = 0, from = 0;
  while (reach < r) {
    const int shift = std::min(2 * reach + 1, r - reach);
    reach += shift;
    const int beyond = r - reach;
    const std::uint8_t* source = padded_[from].data() + r - beyond;
    std::uint8_t* to = beyond == 0 ? out : padded_[1 - from].data() + r - beyond;
    if (operation_ == Operation::erode) {
      erode_step(source, width + 2 * beyond, shift, to);
    } else {
      dilate_step(source, width + 2 * beyond, shift, to);
    }
    from = 1 - from;
  }
}

}  // namespace irloc
