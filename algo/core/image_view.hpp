#pragma once
// Non-owning views of grey images, the currency of every image kernel.

#include <cstdint>
#include <cstddef>
#include <type_traits>
#include <variant>

namespace irloc {

// A width x height grey image whose pixel (x, y) is at data()[y * stride() + x]. The stride is
// counted in pixels, not bytes, and is at least the width (rows may be padded). The view owns
// nothing: whoever made the buffer keeps it alive for as long as views of it are in use.
template <typename Pixel>
class ImageView {
 public:
  ImageView() = default;
  ImageView(Pixel* data, int width, int height, int stride)
      : data_(data), width_(width), height_(height), stride_(stride) {}
  ImageView(Pixel* data, int width, int height) : ImageView(data, width, height, width) {}

  // A mutable view converts to a read-only one, never the other way.
  operator ImageView<const Pixel>() const
    requires(!std::is_const_v<Pixel>)
  {
    return {data_, width_, height_, stride_};
  }

  Pixel* data() const { return data_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int stride() const { return stride_; }
  bool empty() const { return width_ <= 0 || height_ <= 0; }
  bool same_size(int width, int height) const { return width_ == width && height_ == height; }

  Pixel* row(int y) const { return data_ + static_cast<std::ptrdiff_t>(y) * stride_; }
  Pixel& at(int x, int y) const { return row(y)[x]; }

  // The w x h region whose top-left pixel is (x, y); the caller keeps it inside the image.
  ImageView region(int x, int y, int w, int h) const { return {&at(x, y), w, h, stride_}; }

 private:
  Pixel* data_ = nullptr;
  int width_ = 0;
  int height_ = 0;
  int stride_ = 0;
};

using ImageView8 = ImageView<const std::uint8_t>;
using ImageView16 = ImageView<const std::uint16_t>;
using MutableImageView8 = ImageView<std::uint8_t>;
using MutableImageView16 = ImageView<std::uint16_t>;

// A camera frame is 8-bit or, for 10/12-bit sensors, 16-bit; the depth is fixed at start-up.
using GrayImageView = std::variant<ImageView8, ImageView16>;

inline int width_of(const GrayImageView& image) {
  return std::visit([](const auto& view) { return view.width(); }, image);
}
inline int height_of(const GrayImageView& image) {
  return std::visit([](const auto& view) { return view.height(); }, image);
}

}  // namespace irloc
