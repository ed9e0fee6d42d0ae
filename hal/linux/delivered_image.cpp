#include "hal/linux/delivered_image.hpp"

namespace irloc::hal {

PixelLayout pixel_layout_of(const std::string& format) {
  if (format == "R8") return PixelLayout::mono8;
  if (format == "R10" || format == "R12" || format == "R16") return PixelLayout::mono16;
  if (format == "R10_CSI2P") return PixelLayout::packed10;
  if (format == "YUYV") return PixelLayout::yuyv;
  return PixelLayout::y_plane;  // YUV420, NV12
}

ConvertedImage converted_image_for(PixelLayout layout, int width, int height) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  ConvertedImage converted;
  if (layout == PixelLayout::yuyv) converted.pixels8.resize(pixels);
  if (layout == PixelLayout::packed10) converted.pixels16.resize(pixels);
  return converted;
}

GrayImageView grey_image(PixelLayout layout, const std::uint8_t* pixels, int width, int height, std::size_t stride,
                         ConvertedImage& converted) {
  const auto row_of = [&](int y) { return pixels + static_cast<std::size_t>(y) * stride; };
  const std::size_t out_row = static_cast<std::size_t>(width);
  switch (layout) {
    case PixelLayout::mono8:
    case PixelLayout::y_plane:
      return ImageView8(pixels, width, height, static_cast<int>(stride));
    case PixelLayout::mono16:
      return ImageView16(reinterpret_cast<const std::uint16_t*>(pixels), width, height, static_cast<int>(stride / 2));
    case PixelLayout::yuyv:
      for (int y = 0; y < height; ++y) {
        const std::uint8_t* row = row_of(y);
        std::uint8_t* out = converted.pixels8.data() + static_cast<std::size_t>(y) * out_row;
        for (int x = 0; x < width; ++x) out[x] = row[2 * x];
      }
      return ImageView8(converted.pixels8.data(), width, height, width);
    case PixelLayout::packed10:
      for (int y = 0; y < height; ++y) {
        const std::uint8_t* row = row_of(y);
        std::uint16_t* out = converted.pixels16.data() + static_cast<std::size_t>(y) * out_row;
        for (int x = 0; x < width; ++x) {
          const std::uint8_t* group = row + (x / 4) * 5;
          const int low = (group[4] >> (2 * (x % 4))) & 0x3;
          out[x] = static_cast<std::uint16_t>((group[x % 4] << 2) | low);
        }
      }
      return ImageView16(converted.pixels16.data(), width, height, width);
  }
  return ImageView8();
}

}  // namespace irloc::hal
