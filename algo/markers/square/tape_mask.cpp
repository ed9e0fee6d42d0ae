#include "algo/markers/square/tape_mask.hpp"

#include <algorithm>
#include <cassert>
#include <variant>

namespace irloc::square {

TapeMask::TapeMask(int x, int y, int width, int height, int element_radius, int pixel_bits)
    : x_(x), y_(y), width_(width), height_(height), wide_(pixel_bits > 8), thin_lines_(width, height, element_radius) {}

void TapeMask::extract(const GrayImageView& on_frame, const GrayImageView& off_frame, std::uint16_t threshold) {
  assert(std::holds_alternative<ImageView16>(on_frame) == wide_ && on_frame.index() == off_frame.index());
  if (wide_) {
    thin_lines_.extract(std::get<ImageView16>(on_frame).region(x_, y_, width_, height_),
                        std::get<ImageView16>(off_frame).region(x_, y_, width_, height_), threshold);
  } else {
    thin_lines_.extract(std::get<ImageView8>(on_frame).region(x_, y_, width_, height_),
                        std::get<ImageView8>(off_frame).region(x_, y_, width_, height_),
                        static_cast<std::uint8_t>(std::min<std::uint16_t>(threshold, 255)));
  }
}

}  // namespace irloc::square
