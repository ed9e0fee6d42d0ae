#pragma once
// An owning grey image: allocated once at start-up, viewed per frame.

#include <vector>

#include "algo/core/image_view.hpp"

namespace irloc {

template <typename Pixel>
class Image {
 public:
  Image() = default;
  Image(int width, int height)
      : pixels_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)),
        width_(width),
        height_(height) {}

  ImageView<Pixel> view() { return {pixels_.data(), width_, height_}; }
  ImageView<const Pixel> view() const { return {pixels_.data(), width_, height_}; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  std::vector<Pixel> pixels_;
  int width_ = 0;
  int height_ = 0;
};

using Image8 = Image<std::uint8_t>;
using Image16 = Image<std::uint16_t>;

}  // namespace irloc
