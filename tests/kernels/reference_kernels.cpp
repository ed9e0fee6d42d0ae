#include "tests/kernels/reference_kernels.hpp"

#include <algorithm>

namespace irloc::reference {
namespace {

template <bool kErode>
void filter(ImageView8 in, StructuringElement element, MutableImageView8 out) {
  const int r = element.radius;
  for (int y = 0; y < in.height(); ++y) {
    for (int x = 0; x < in.width(); ++x) {
      std::uint8_t value = in.at(x, y);
      for (int dy = -r; dy <= r; ++dy) {
        for (int dx = -r; dx <= r; ++dx) {
          if (element.shape == ElementShape::cross && dx != 0 && dy != 0) continue;
          const int sx = x + dx;
          const int sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= in.width() || sy >= in.height()) continue;
          value = kErode ? std::min(value, in.at(sx, sy)) : std::max(value, in.at(sx, sy));
        }
      }
      out.at(x, y) = value;
    }
  }
}

}  // namespace

void erode(ImageView8 in, StructuringElement element, MutableImageView8 out) { filter<true>(in, element, out); }
void dilate(ImageView8 in, StructuringElement element, MutableImageView8 out) { filter<false>(in, element, out); }

template <typename Pixel>
std::vector<Blob> blobs(ImageView<const Pixel> intensity, Pixel threshold, ImageView<std::int32_t> labels) {
  const int width = intensity.width();
  const int height = intensity.height();
  std::vector<std::int32_t> label(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0);
  const auto at = [&](int x, int y) -> std::int32_t& { return label[static_cast<std::size_t>(y) * width + x]; };
  std::vector<Blob> result;
  std::vector<std::pair<int, int>> stack;
  for (int y0 = 0; y0 < height; ++y0) {
    for (int x0 = 0; x0 < width; ++x0) {
      if (intensity.at(x0, y0) <= threshold || at(x0, y0) != 0) continue;
      result.emplace_back();
      Blob& blob = result.back();
      const auto id = static_cast<std::int32_t>(result.size());
      blob.x_min = blob.x_max = x0;
      blob.y_min = blob.y_max = y0;
      at(x0, y0) = id;
      stack.assign(1, {x0, y0});
      while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        const std::uint64_t value = intensity.at(x, y);
        const auto ux = static_cast<std::uint64_t>(x);
        const auto uy = static_cast<std::uint64_t>(y);
        ++blob.area;
        blob.x_min = std::min(blob.x_min, x);
        blob.x_max = std::max(blob.x_max, x);
        blob.y_min = std::min(blob.y_min, y);
        blob.y_max = std::max(blob.y_max, y);
        blob.sum_x += ux;
        blob.sum_y += uy;
        blob.sum_i += value;
        blob.sum_ix += value * ux;
        blob.sum_iy += value * uy;
        blob.sum_ixx += value * ux * ux;
        blob.sum_iyy += value * uy * uy;
        blob.sum_ixy += value * ux * uy;
        blob.peak = std::max<std::uint32_t>(blob.peak, static_cast<std::uint32_t>(value));
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx;
            const int ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            if (intensity.at(nx, ny) <= threshold || at(nx, ny) != 0) continue;
            at(nx, ny) = id;
            stack.emplace_back(nx, ny);
          }
        }
      }
    }
  }
  if (!labels.empty()) {
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) labels.at(x, y) = at(x, y);
    }
  }
  return result;
}

template std::vector<Blob> blobs(ImageView8, std::uint8_t, ImageView<std::int32_t>);
template std::vector<Blob> blobs(ImageView16, std::uint16_t, ImageView<std::int32_t>);

}  // namespace irloc::reference
