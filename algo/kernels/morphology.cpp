#include "algo/kernels/morphology.hpp"

#include <algorithm>
#include <cassert>

#include "algo/kernels/simd_row.hpp"

namespace irloc {
namespace {

template <bool kErode>
std::uint8_t extreme(std::uint8_t a, std::uint8_t b) {
  return kErode ? std::min(a, b) : std::max(a, b);
}

template <bool kErode>
simd::Vec<std::uint8_t> vector_extreme(simd::Vec<std::uint8_t> a, simd::Vec<std::uint8_t> b) {
  return kErode ? simd::vector_min(a, b) : simd::vector_max(a, b);
}

// acc[x] = extreme(acc[x], src[x]) for x < n.
template <bool kErode>
void combine_row(std::uint8_t* acc, const std::uint8_t* src, int n) {
  constexpr int lanes = simd::kLanes<std::uint8_t>;
  int x = 0;
  for (; x + lanes <= n; x += lanes) {
    simd::store(acc + x, vector_extreme<kErode>(simd::load(acc + x), simd::load(src + x)));
  }
  for (; x < n; ++x) acc[x] = extreme<kErode>(acc[x], src[x]);
}

// out[x] = extreme of src[x - r .. x + r] clipped to [0, n).
template <bool kErode>
void window_row(const std::uint8_t* src, int n, int r, std::uint8_t* out) {
  constexpr int lanes = simd::kLanes<std::uint8_t>;
  const int inner_begin = std::min(r, n);
  const int inner_end = std::max(inner_begin, n - r);
  const auto clipped = [&](int x) {
    std::uint8_t v = src[x];
    for (int k = std::max(0, x - r); k <= std::min(n - 1, x + r); ++k) v = extreme<kErode>(v, src[k]);
    return v;
  };
  for (int x = 0; x < inner_begin; ++x) out[x] = clipped(x);
  int x = inner_begin;
  for (; x + lanes <= inner_end; x += lanes) {
    simd::Vec<std::uint8_t> v = simd::load(src + x - r);
    for (int k = -r + 1; k <= r; ++k) v = vector_extreme<kErode>(v, simd::load(src + x + k));
    simd::store(out + x, v);
  }
  for (; x < n; ++x) out[x] = clipped(x);
}

}  // namespace

Morphology::Morphology(int max_width) : column_extreme_(static_cast<std::size_t>(std::max(max_width, 1))) {}

void Morphology::erode(ImageView8 in, StructuringElement element, MutableImageView8 out) {
  filter<true>(in, element, out);
}

void Morphology::dilate(ImageView8 in, StructuringElement element, MutableImageView8 out) {
  filter<false>(in, element, out);
}

template <bool kErode>
void Morphology::filter(ImageView8 in, StructuringElement element, MutableImageView8 out) {
  assert(in.same_size(out.width(), out.height()));
  assert(in.width() <= static_cast<int>(column_extreme_.size()) && element.radius >= 0);
  const int width = in.width();
  const int height = in.height();
  const int r = element.radius;
  std::uint8_t* column = column_extreme_.data();
  for (int y = 0; y < height; ++y) {
    // Vertical pass: the extreme over the element's rows that lie inside the image.
    const int top = std::max(0, y - r);
    const int bottom = std::min(height - 1, y + r);
    std::copy_n(in.row(top), width, column);
    for (int row = top + 1; row <= bottom; ++row) combine_row<kErode>(column, in.row(row), width);
    std::uint8_t* dst = out.row(y);
    if (element.shape == ElementShape::square) {
      // The box is separable: the horizontal window of the column extremes.
      window_row<kErode>(column, width, r, dst);
    } else {
      // The cross is the union of its row and its column.
      window_row<kErode>(in.row(y), width, r, dst);
      combine_row<kErode>(dst, column, width);
    }
  }
}

}  // namespace irloc
