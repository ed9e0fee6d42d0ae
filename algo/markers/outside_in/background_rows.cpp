#include "algo/markers/outside_in/background_rows.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "algo/kernels/wide_vectors.hpp"

namespace irloc::outside_in::background_rows {
namespace {

using wide::load;
using wide::store;

// The vectors of one kernel width: kLanes pixels as 16-bit lanes (Wide16), their bytes as a
// half-width vector (Half8), and 32-bit lanes of half as many pixels (Wide32) for the rescale.
template <int kBytes>
struct Lanes {
  static constexpr int kPixels = kBytes / 2;
  using Wide16 = wide::Vec<std::uint16_t, kBytes>;
  using Half8 = wide::Vec<std::uint8_t, kBytes / 2>;
  using Wide32 = wide::Vec<std::uint32_t, kBytes>;
  using Half16 = wide::Vec<std::uint16_t, kBytes / 2>;

  // Lane i of the result is low[i] | high[i] << 8 (little-endian lanes). Written as a shuffle rather than a conversion:
  // GCC 12 builds the AVX2 conversions from two 128-bit halves, and the shuffle as one
  // zero-extension (high 0) or one byte shuffle (high = low).
  template <std::size_t... kIndex>
  __attribute__((always_inline)) static Wide16 interleave(const Half8& low, const Half8& high, std::index_sequence<kIndex...>) {
    return reinterpret_cast<Wide16>(__builtin_shufflevector(low, high, ((kIndex % 2) * kPixels + kIndex / 2)...));
  }
  __attribute__((always_inline)) static Wide16 interleave(const Half8& low, const Half8& high) {
    return interleave(low, high, std::make_index_sequence<kBytes>{});
  }
  // kPixels bytes widened to 16-bit lanes.
  __attribute__((always_inline)) static Wide16 widen(const std::uint8_t* p) { return interleave(load<Half8>(p), Half8{}); }
  // A 0/255 mask's kPixels bytes as 16-bit lanes of 0 / 0xFFFF.
  __attribute__((always_inline)) static Wide16 widen_mask(const std::uint8_t* p) {
    const Half8 mask = load<Half8>(p);
    return interleave(mask, mask);
  }
  // Whether kPixels bytes are all 0.
  __attribute__((always_inline)) static bool all_zero(const std::uint8_t* p) {
    using Words = wide::Vec<std::uint64_t, kBytes / 2>;
    const Words words = load<Words>(p);
    std::uint64_t any = 0;
    for (int k = 0; k < kBytes / 16; ++k) any |= words[k];
    return any == 0;
  }
  // The low bytes of 16-bit lanes (values < 256, or masks) stored as kPixels bytes.
  __attribute__((always_inline)) static void narrow_store(std::uint8_t* p, const Wide16& v) { store(p, __builtin_convertvector(v, Half8)); }
};

template <typename V>
__attribute__((always_inline)) inline V min_of(const V& a, const V& b) {
  return a < b ? a : b;
}

// max(a - b, 0) of unsigned lanes.
template <typename V>
__attribute__((always_inline)) inline V saturated_difference(const V& a, const V& b) {
  return a - min_of(a, b);
}

// ceil(v / 2^shift) - 1 of unsigned lanes, modulo 2^16: (v >> shift) - (no low bit set), a true
// lane being -1. The difference of two is the difference of the ceilings.
template <typename V>
__attribute__((always_inline)) inline V ceil_shift_less_one(const V& v, int shift, const V& low_bits) {
  return (v >> shift) + reinterpret_cast<V>((v & low_bits) == 0);
}

// Runs kernel(offset, count) over [0, n) in groups of kPixels; the last partial group goes through
// bounce buffers that the kernel is handed instead of the rows (see each caller).
template <int kPixels, typename Group, typename Tail>
__attribute__((always_inline)) inline void for_each_group(int n, Group group, Tail tail) {
  int x = 0;
  for (; x + kPixels <= n; x += kPixels) group(x);
  if (x < n) tail(x, n - x);
}

template <int kBytes>
__attribute__((always_inline)) inline void rescale_row(std::uint16_t* cells, int n, std::uint32_t gain_q8) {
  using L = Lanes<kBytes>;
  constexpr int kGroup = kBytes / 4;  // 32-bit lanes
  const typename L::Wide32 gain = typename L::Wide32{} + gain_q8;
  const typename L::Wide32 saturated = typename L::Wide32{} + 0xFFFFu;
  const auto group = [&](std::uint16_t* p) {
    // cell, gain_q8 <= 0xFFFF: the product and the rounding term stay below 2^32.
    const typename L::Wide32 wide_cells = __builtin_convertvector(load<typename L::Half16>(p), typename L::Wide32);
    const typename L::Wide32 scaled = min_of((wide_cells * gain + 128) >> 8, saturated);
    store(p, __builtin_convertvector(scaled, typename L::Half16));
  };
  for_each_group<kGroup>(
      n, [&](int x) { group(cells + x); },
      [&](int x, int count) {
        std::uint16_t bounce[kGroup] = {};
        std::copy_n(cells + x, count, bounce);
        group(bounce);
        std::copy_n(bounce, count, cells + x);
      });
}

// motion[i] = 255 where |frame - previous| > still_levels, else 0, then previous[i] = frame[i]: in
// byte lanes, twice the pixels of a 16-bit vector.
template <int kBytes>
__attribute__((always_inline)) inline void motion_row(const std::uint8_t* frame, std::uint8_t* previous, int n,
                                                      std::uint8_t still_levels, std::uint8_t* motion) {
  using B = wide::Vec<std::uint8_t, kBytes>;
  const B still = B{} + still_levels;
  const auto group = [&](const std::uint8_t* in, std::uint8_t* last, std::uint8_t* moved) {
    const B grey = load<B>(in), before = load<B>(last);
    const B low = min_of(grey, before);
    const B high = grey > before ? grey : before;
    store(moved, reinterpret_cast<B>(high - low > still));
    store(last, grey);
  };
  for_each_group<kBytes>(
      n, [&](int x) { group(frame + x, previous + x, motion + x); },
      [&](int x, int tail) {
        std::uint8_t in[kBytes] = {}, last[kBytes] = {}, moved[kBytes];
        std::copy_n(frame + x, tail, in);
        std::copy_n(previous + x, tail, last);
        group(in, last, moved);
        std::copy_n(moved, tail, motion + x);
        std::copy_n(last, tail, previous + x);
      });
}

template <int kBytes>
__attribute__((always_inline)) inline std::uint32_t classify_row(const std::uint8_t* frame, const std::uint16_t* cells,
                                                                 std::uint8_t* previous, int n,
                                                                 const ClassifyParams& params, std::uint8_t* foreground,
                                                                 std::uint8_t* motion) {
  using L = Lanes<kBytes>;
  using V = typename L::Wide16;
  const V threshold = V{} + params.threshold_q8_8;
  const V ratio = V{} + params.shadow_ratio_q8;
  motion_row<kBytes>(frame, previous, n, params.still_levels, motion);
  V count = {};
  const auto group = [&](const std::uint8_t* in, const std::uint16_t* cell_row, std::uint8_t* fg) {
    const V pixel = L::widen(in) << 8;  // Q8.8, <= 0xFF00
    const V cell = load<V>(cell_row);
    // A shadow is pixel < cell and pixel * 256 >= ratio * cell, i.e. pixel >= ceil(ratio * cell / 256)
    // = ratio * (cell >> 8) + ceil(ratio * (cell & 255) / 256): with ratio <= 256 each product
    // is at most 256 * 255 and the sum at most 0xFF00 + 0xFF.
    const V shadow_floor = ratio * (cell >> 8) + ((ratio * (cell & 0xFF) + 0xFF) >> 8);
    // Foreground: pixel > cell + threshold, or pixel < cell - threshold and below the shadow floor,
    // each a saturated difference that is not 0.
    const V brighter = saturated_difference(saturated_difference(pixel, threshold), cell);
    const V darker = saturated_difference(min_of(saturated_difference(cell, threshold), shadow_floor), pixel);
    const V is_foreground = (brighter | darker) != 0;
    L::narrow_store(fg, is_foreground);
    count -= is_foreground;  // a true lane is -1
  };
  constexpr int kGroup = L::kPixels;
  for_each_group<kGroup>(
      n, [&](int x) { group(frame + x, cells + x, foreground + x); },
      [&](int x, int tail) {
        // Lanes past the row hold 0: never foreground.
        std::uint8_t in[kGroup] = {}, fg[kGroup];
        std::uint16_t cell_row[kGroup] = {};
        std::copy_n(frame + x, tail, in);
        std::copy_n(cells + x, tail, cell_row);
        group(in, cell_row, fg);
        std::copy_n(fg, tail, foreground + x);
      });
  std::uint32_t total = 0;
  for (int k = 0; k < kGroup; ++k) total += count[k];
  return total;
}

// The cell moved toward target by ceil(|target - cell| / 2^shift): a still scene converges to the
// grey level. target <= 0xFF00, so no lane leaves [0, 0xFFFF].
template <typename V>
__attribute__((always_inline)) inline V followed_cell(const V& cell, const V& target, int shift, const V& low_bits) {
  const V low = min_of(target, cell);
  return cell + ceil_shift_less_one(target - low, shift, low_bits) - ceil_shift_less_one(cell - low, shift, low_bits);
}

// One group of follow(): each cell follows the frame, its still count is 0.
template <int kBytes>
__attribute__((always_inline)) inline void follow_group(const std::uint8_t* in, std::uint16_t* cell_row, std::uint8_t* still,
                                                        int shift, const typename Lanes<kBytes>::Wide16& low_bits) {
  using L = Lanes<kBytes>;
  store(cell_row, followed_cell(load<typename L::Wide16>(cell_row), L::widen(in) << 8, shift, low_bits));
  store(still, typename L::Half8{});
}

template <int kBytes>
__attribute__((always_inline)) inline void update_row(const std::uint8_t* frame, const std::uint8_t* foreground,
                                                      const std::uint8_t* motion, const std::uint8_t* grown,
                                                      const std::uint8_t* motion_grown, const std::uint8_t* protect,
                                                      int n, const UpdateParams& params, std::uint16_t* cells,
                                                      std::uint8_t* still_count) {
  using L = Lanes<kBytes>;
  using V = typename L::Wide16;
  const int shift = params.update_shift;
  const V low_bits = V{} + static_cast<std::uint16_t>((1u << shift) - 1);
  const V absorb = V{} + params.absorb_frames;
  const auto group = [&](const std::uint8_t* in, const std::uint8_t* fg, const std::uint8_t* moved,
                         const std::uint8_t* near_fg, const std::uint8_t* near_motion, const std::uint8_t* guarded,
                         std::uint16_t* cell_row, std::uint8_t* still) {
    // No foreground within the gate radius (most groups): nothing is gated or counted.
    if (L::all_zero(near_fg)) {
      follow_group<kBytes>(in, cell_row, still, shift, low_bits);
      return;
    }
    const V target = L::widen(in) << 8;
    const V cell = load<V>(cell_row);
    const V is_foreground = L::widen_mask(fg);
    const V is_protected = L::widen_mask(guarded);
    const V gated = L::widen_mask(near_fg) & (L::widen_mask(moved) | is_protected);
    const V follows = ~(is_foreground | gated);
    const V counts = is_foreground & ~(L::widen_mask(near_motion) | is_protected);
    const V counted = (L::widen(still) + 1) & counts;  // <= absorb_frames <= 255
    const V absorbed = counted >= absorb;
    const V followed = followed_cell(cell, target, shift, low_bits);
    store(cell_row, (followed & follows) | (target & absorbed) | (cell & ~(follows | absorbed)));
    L::narrow_store(still, counted & ~absorbed);
  };
  constexpr int kGroup = L::kPixels;
  for_each_group<kGroup>(
      n,
      [&](int x) {
        group(frame + x, foreground + x, motion + x, grown + x, motion_grown + x, protect + x, cells + x,
              still_count + x);
      },
      [&](int x, int tail) {
        // Lanes past the row: every mask 0 (the cell follows), results discarded.
        std::uint8_t in[kGroup] = {}, fg[kGroup] = {}, moved[kGroup] = {}, near_fg[kGroup] = {},
                     near_motion[kGroup] = {}, guarded[kGroup] = {}, still[kGroup] = {};
        std::uint16_t cell_row[kGroup] = {};
        std::copy_n(frame + x, tail, in);
        std::copy_n(foreground + x, tail, fg);
        std::copy_n(motion + x, tail, moved);
        std::copy_n(grown + x, tail, near_fg);
        std::copy_n(motion_grown + x, tail, near_motion);
        std::copy_n(protect + x, tail, guarded);
        std::copy_n(still_count + x, tail, still);
        std::copy_n(cells + x, tail, cell_row);
        group(in, fg, moved, near_fg, near_motion, guarded, cell_row, still);
        std::copy_n(cell_row, tail, cells + x);
        std::copy_n(still, tail, still_count + x);
      });
}

template <int kBytes>
__attribute__((always_inline)) inline void follow_row(const std::uint8_t* frame, int n, int shift, std::uint16_t* cells,
                                                      std::uint8_t* still_count) {
  using L = Lanes<kBytes>;
  using V = typename L::Wide16;
  const V low_bits = V{} + static_cast<std::uint16_t>((1u << shift) - 1);
  const auto group = [&](const std::uint8_t* in, std::uint16_t* cell_row, std::uint8_t* still) {
    follow_group<kBytes>(in, cell_row, still, shift, low_bits);
  };
  constexpr int kGroup = L::kPixels;
  for_each_group<kGroup>(
      n, [&](int x) { group(frame + x, cells + x, still_count + x); },
      [&](int x, int tail) {
        std::uint8_t in[kGroup] = {}, still[kGroup];
        std::uint16_t cell_row[kGroup] = {};
        std::copy_n(frame + x, tail, in);
        std::copy_n(cells + x, tail, cell_row);
        group(in, cell_row, still);
        std::copy_n(cell_row, tail, cells + x);
        std::copy_n(still, tail, still_count + x);
      });
}

IRLOC_WIDE_KERNEL_16 void rescale_wide(std::uint16_t* cells, int n, std::uint32_t gain_q8) {
  rescale_row<16>(cells, n, gain_q8);
}
IRLOC_WIDE_KERNEL_32(void rescale_wide(std::uint16_t* cells, int n, std::uint32_t gain_q8) {
  rescale_row<32>(cells, n, gain_q8);
})

IRLOC_WIDE_KERNEL_16 std::uint32_t classify_wide(const std::uint8_t* frame, const std::uint16_t* cells,
                                                 std::uint8_t* previous, int n, const ClassifyParams& params,
                                                 std::uint8_t* foreground, std::uint8_t* motion) {
  return classify_row<16>(frame, cells, previous, n, params, foreground, motion);
}
IRLOC_WIDE_KERNEL_32(std::uint32_t classify_wide(const std::uint8_t* frame, const std::uint16_t* cells,
                                                 std::uint8_t* previous, int n, const ClassifyParams& params,
                                                 std::uint8_t* foreground, std::uint8_t* motion) {
  return classify_row<32>(frame, cells, previous, n, params, foreground, motion);
})

IRLOC_WIDE_KERNEL_16 void update_wide(const std::uint8_t* frame, const std::uint8_t* foreground,
                                      const std::uint8_t* motion, const std::uint8_t* grown,
                                      const std::uint8_t* motion_grown, const std::uint8_t* protect, int n,
                                      const UpdateParams& params, std::uint16_t* cells, std::uint8_t* still_count) {
  update_row<16>(frame, foreground, motion, grown, motion_grown, protect, n, params, cells, still_count);
}
IRLOC_WIDE_KERNEL_32(void update_wide(const std::uint8_t* frame, const std::uint8_t* foreground,
                                      const std::uint8_t* motion, const std::uint8_t* grown,
                                      const std::uint8_t* motion_grown, const std::uint8_t* protect, int n,
                                      const UpdateParams& params, std::uint16_t* cells, std::uint8_t* still_count) {
  update_row<32>(frame, foreground, motion, grown, motion_grown, protect, n, params, cells, still_count);
})

IRLOC_WIDE_KERNEL_16 void follow_wide(const std::uint8_t* frame, int n, int shift, std::uint16_t* cells,
                                      std::uint8_t* still_count) {
  follow_row<16>(frame, n, shift, cells, still_count);
}
IRLOC_WIDE_KERNEL_32(void follow_wide(const std::uint8_t* frame, int n, int shift, std::uint16_t* cells,
                                      std::uint8_t* still_count) {
  follow_row<32>(frame, n, shift, cells, still_count);
})

}  // namespace

void rescale(std::uint16_t* cells, int n, std::uint32_t gain_q8) { rescale_wide(cells, n, gain_q8); }

std::uint32_t classify(const std::uint8_t* frame, const std::uint16_t* cells, std::uint8_t* previous, int n,
                       const ClassifyParams& params, std::uint8_t* foreground, std::uint8_t* motion) {
  return classify_wide(frame, cells, previous, n, params, foreground, motion);
}

void update(const std::uint8_t* frame, const std::uint8_t* foreground, const std::uint8_t* motion,
            const std::uint8_t* grown, const std::uint8_t* motion_grown, const std::uint8_t* protect, int n,
            const UpdateParams& params, std::uint16_t* cells, std::uint8_t* still_count) {
  update_wide(frame, foreground, motion, grown, motion_grown, protect, n, params, cells, still_count);
}

void follow(const std::uint8_t* frame, int n, int update_shift, std::uint16_t* cells, std::uint8_t* still_count) {
  follow_wide(frame, n, update_shift, cells, still_count);
}

}  // namespace irloc::outside_in::background_rows
