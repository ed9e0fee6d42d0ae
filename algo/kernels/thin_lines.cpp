#include "algo/kernels/thin_lines.hpp"

#include <cassert>

#include "algo/kernels/simd_row.hpp"
#include "algo/kernels/threshold.hpp"

namespace irloc {

ThinLineExtractor::ThinLineExtractor(int width, int height, StructuringElement element)
    : element_(element),
      morphology_(width),
      binary_(width, height),
      eroded_(width, height),
      opened_(width, height) {}

void ThinLineExtractor::extract(ImageView8 image, std::uint8_t threshold, MutableImageView8 lines) {
  threshold_binary(image, threshold, 255, binary_.view());
  open_and_subtract(lines);
}

void ThinLineExtractor::extract(ImageView16 image, std::uint16_t threshold, MutableImageView8 lines) {
  threshold_binary(image, threshold, 255, binary_.view());
  open_and_subtract(lines);
}

void ThinLineExtractor::open_and_subtract(MutableImageView8 lines) {
  assert(lines.same_size(binary_.width(), binary_.height()));
  morphology_.erode(binary_.view(), element_, eroded_.view());
  morphology_.dilate(eroded_.view(), element_, opened_.view());
  // The opening never exceeds the mask, so binary - opened is 255 exactly where only the mask is set.
  const ImageView8 binary = binary_.view();
  const ImageView8 opened = opened_.view();
  constexpr int lanes = simd::kLanes<std::uint8_t>;
  for (int y = 0; y < lines.height(); ++y) {
    const std::uint8_t* b = binary.row(y);
    const std::uint8_t* o = opened.row(y);
    std::uint8_t* d = lines.row(y);
    int x = 0;
    for (; x + lanes <= lines.width(); x += lanes) {
      simd::store(d + x, simd::vector_saturating_subtract(simd::load(b + x), simd::load(o + x)));
    }
    for (; x < lines.width(); ++x) d[x] = simd::saturating_subtract(b[x], o[x]);
  }
}

}  // namespace irloc
