#include "algo/markers/square/tape_mask.hpp"

#include <algorithm>
#include <cassert>
#include <variant>

#include "algo/kernels/difference.hpp"

namespace irloc {

TapeMask::TapeMask(int x, int y, int width, int height, int element_radius, int pixel_bits)
    : x_(x),
      y_(y),
      wide_(pixel_bits > 8),
      thin_lines_(width, height, StructuringElement{ElementShape::square, element_radius}),
      difference8_(wide_ ? Image8() : Image8(width, height)),
      difference16_(wide_ ? Image16(width, height) : Image16()),
      mask_(width, height) {}

void TapeMask::extract(const GrayImageView& on_frame, const GrayImageView& off_frame, std::uint16_t threshold) {
  assert(std::holds_alternative<ImageView16>(on_frame) == wide_ && on_frame.index() == off_frame.index());
  const int width = mask_.width();
  const int height = mask_.height();
  if (wide_) {
    subtract_saturating(std::get<ImageView16>(on_frame).region(x_, y_, width, height),
                        std::get<ImageView16>(off_frame).region(x_, y_, width, height), difference16_.view());
    thin_lines_.extract(ImageView16(difference16_.view()), threshold, mask_.view());
  } else {
    subtract_saturating(std::get<ImageView8>(on_frame).region(x_, y_, width, height),
                        std::get<ImageView8>(off_frame).region(x_, y_, width, height), difference8_.view());
    thin_lines_.extract(ImageView8(difference8_.view()), static_cast<std::uint8_t>(std::min<std::uint16_t>(threshold, 255)),
                        mask_.view());
  }
}

}  // namespace irloc
