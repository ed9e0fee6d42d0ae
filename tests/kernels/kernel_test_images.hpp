#pragma once
// Test images for the kernel suites: padded strides, random content, synthetic IR strobe pairs.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "algo/core/image_view.hpp"

namespace irloc::test {

// An owning image whose rows are padded to stride = width + padding (padding filled with a
// marker value, so a kernel that reads or writes past the width shows up).
template <typename Pixel>
class PaddedImage {
 public:
  PaddedImage(int width, int height, int padding = 0, Pixel pad_value = 0)
      : width_(width), height_(height), stride_(width + padding),
        pixels_(static_cast<std::size_t>(stride_) * static_cast<std::size_t>(std::max(height, 1)), pad_value) {
    for (int y = 0; y < height; ++y) std::fill_n(view().row(y), width, Pixel{0});
  }
  ImageView<Pixel> view() { return {pixels_.data(), width_, height_, stride_}; }
  ImageView<const Pixel> view() const { return {pixels_.data(), width_, height_, stride_}; }
  Pixel& at(int x, int y) { return view().at(x, y); }
  Pixel at(int x, int y) const { return view().at(x, y); }
  int width() const { return width_; }
  int height() const { return height_; }
  int stride() const { return stride_; }
  const std::vector<Pixel>& storage() const { return pixels_; }
  void fill(Pixel value) {
    for (int y = 0; y < height_; ++y) std::fill_n(view().row(y), width_, value);
  }

 private:
  int width_;
  int height_;
  int stride_;
  std::vector<Pixel> pixels_;
};

template <typename Pixel>
void fill_random(PaddedImage<Pixel>& image, std::mt19937& rng, int max_value) {
  std::uniform_int_distribution<int> value(0, max_value);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) image.at(x, y) = static_cast<Pixel>(value(rng));
  }
}

// Random binary mask (0 / 255) with the given density of set pixels in percent.
inline void fill_random_mask(PaddedImage<std::uint8_t>& image, std::mt19937& rng, int percent) {
  std::uniform_int_distribution<int> roll(0, 99);
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) image.at(x, y) = roll(rng) < percent ? 255 : 0;
  }
}

// A sparse IR strobe pair: a dim noisy ceiling with static lamps in both frames, plus Gaussian
// retro-reflective dots in the LED-on frame only. max_value: 255 or (1 << bits) - 1.
template <typename Pixel>
void make_strobe_pair(PaddedImage<Pixel>& on, PaddedImage<Pixel>& off, std::mt19937& rng, int dots,
                      int max_value = 255) {
  const double scale = max_value / 255.0;
  std::normal_distribution<double> noise(0.0, 2.0 * scale);
  const int width = on.width();
  const int height = on.height();
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double ceiling = (20.0 + 10.0 * std::sin(x * 0.01) * std::cos(y * 0.013)) * scale;
      // A static lamp, bright in both frames: must cancel.
      const double lamp = (std::hypot(x - width * 0.7, y - height * 0.3) < height * 0.08) ? 200.0 * scale : 0.0;
      const auto clamp = [&](double v) { return static_cast<Pixel>(std::clamp(v, 0.0, static_cast<double>(max_value))); };
      off.at(x, y) = clamp(ceiling + lamp + noise(rng));
      on.at(x, y) = clamp(ceiling + lamp + 3.0 * scale + noise(rng));  // the LEDs light the ceiling a little
    }
  }
  std::uniform_real_distribution<double> where_x(4.0, width - 5.0);
  std::uniform_real_distribution<double> where_y(4.0, height - 5.0);
  std::uniform_real_distribution<double> sigma(0.8, 2.5);
  for (int d = 0; d < dots; ++d) {
    const double cx = where_x(rng);
    const double cy = where_y(rng);
    const double s = sigma(rng);
    const int reach = static_cast<int>(std::ceil(3 * s));
    for (int y = std::max(0, static_cast<int>(cy) - reach); y <= std::min(height - 1, static_cast<int>(cy) + reach); ++y) {
      for (int x = std::max(0, static_cast<int>(cx) - reach); x <= std::min(width - 1, static_cast<int>(cx) + reach); ++x) {
        const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
        const double added = 180.0 * scale * std::exp(-r2 / (2 * s * s));
        on.at(x, y) = static_cast<Pixel>(std::min<double>(max_value, on.at(x, y) + added));
      }
    }
  }
}

}  // namespace irloc::test
