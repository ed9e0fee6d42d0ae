#include "algo/kernels/difference.hpp"

#include <cassert>

#include "algo/kernels/simd_row.hpp"

namespace irloc {
namespace {

template <typename Pixel>
void subtract_rows(ImageView<const Pixel> on, ImageView<const Pixel> off, ImageView<Pixel> out) {
  assert(on.same_size(off.width(), off.height()) && on.same_size(out.width(), out.height()));
  constexpr int lanes = simd::kLanes<Pixel>;
  const int width = on.width();
  for (int y = 0; y < on.height(); ++y) {
    const Pixel* a = on.row(y);
    const Pixel* b = off.row(y);
    Pixel* d = out.row(y);
    int x = 0;
    for (; x + lanes <= width; x += lanes) {
      simd::store(d + x, simd::vector_saturating_subtract(simd::load(a + x), simd::load(b + x)));
    }
    for (; x < width; ++x) d[x] = simd::saturating_subtract(a[x], b[x]);
  }
}

}  // namespace

void subtract_saturating(ImageView8 on, ImageView8 off, MutableImageView8 out) { subtract_rows(on, off, out); }
void subtract_saturating(ImageView16 on, ImageView16 off, MutableImageView16 out) { subtract_rows(on, off, out); }

}  // namespace irloc
