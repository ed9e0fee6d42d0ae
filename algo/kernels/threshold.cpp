#include "algo/kernels/threshold.hpp"

#include <cassert>

#include "algo/kernels/simd_row.hpp"

namespace irloc {

void threshold_binary(ImageView8 in, std::uint8_t threshold, std::uint8_t max_value, MutableImageView8 out) {
  assert(in.same_size(out.width(), out.height()));
  constexpr int lanes = simd::kLanes<std::uint8_t>;
  const simd::Vec<std::uint8_t> limit = simd::Vec<std::uint8_t>{} + threshold;
  const simd::Vec<std::uint8_t> high = simd::Vec<std::uint8_t>{} + max_value;
  for (int y = 0; y < in.height(); ++y) {
    const std::uint8_t* src = in.row(y);
    std::uint8_t* dst = out.row(y);
    int x = 0;
    for (; x + lanes <= in.width(); x += lanes) {
      // A vector comparison yields all-ones lanes where true: mask max_value with it.
      const auto above = reinterpret_cast<simd::Vec<std::uint8_t>>(simd::load(src + x) > limit);
      simd::store(dst + x, above & high);
    }
    for (; x < in.width(); ++x) dst[x] = src[x] > threshold ? max_value : 0;
  }
}

// A plain loop: GCC vectorizes it (compare, then narrow 16 -> 8 bits) on x86-64 and aarch64.
void threshold_binary(ImageView16 in, std::uint16_t threshold, std::uint8_t max_value, MutableImageView8 out) {
  assert(in.same_size(out.width(), out.height()));
  for (int y = 0; y < in.height(); ++y) {
    const std::uint16_t* src = in.row(y);
    std::uint8_t* dst = out.row(y);
    for (int x = 0; x < in.width(); ++x) dst[x] = src[x] > threshold ? max_value : 0;
  }
}

}  // namespace irloc
