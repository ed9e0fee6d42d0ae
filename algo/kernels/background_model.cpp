#include "algo/kernels/background_model.hpp"

#include <cassert>
#include <stdexcept>

namespace irloc {
namespace {

BackgroundConfig checked(const BackgroundConfig& config) {
  if (config.width <= 0 || config.height <= 0) throw std::invalid_argument("BackgroundModel: size must be positive");
  if (config.update_shift < 0 || config.update_shift > 8) {
    throw std::invalid_argument("BackgroundModel: update_shift must be 0..8");
  }
  return config;
}

}  // namespace

BackgroundModel::BackgroundModel(const BackgroundConfig& config)
    : config_(checked(config)),
      cells_(static_cast<std::size_t>(config.width) * static_cast<std::size_t>(config.height)) {}

void BackgroundModel::reset(ImageView8 frame) { reset_from(frame); }
void BackgroundModel::reset(ImageView16 frame) { reset_from(frame); }
BackgroundResult BackgroundModel::apply(ImageView8 frame, MutableImageView8 foreground) {
  return apply_to(frame, foreground);
}
BackgroundResult BackgroundModel::apply(ImageView16 frame, MutableImageView8 foreground) {
  return apply_to(frame, foreground);
}

template <typename Pixel>
void BackgroundModel::reset_from(ImageView<const Pixel> frame) {
  assert(frame.same_size(config_.width, config_.height));
  for (int y = 0; y < frame.height(); ++y) {
    std::uint32_t* cell = &cells_[index(0, y)];
    const Pixel* pixel = frame.row(y);
    for (int x = 0; x < frame.width(); ++x) cell[x] = static_cast<std::uint32_t>(pixel[x]) << 8;
  }
}

template <typename Pixel>
BackgroundResult BackgroundModel::apply_to(ImageView<const Pixel> frame, MutableImageView8 foreground) {
  assert(frame.same_size(config_.width, config_.height) && foreground.same_size(config_.width, config_.height));
  BackgroundResult result;
  // Pass 1: the foreground mask and its size (a plain loop the compiler vectorizes).
  const std::int32_t threshold = static_cast<std::int32_t>(config_.foreground_threshold);
  for (int y = 0; y < frame.height(); ++y) {
    const std::uint32_t* cell = &cells_[index(0, y)];
    const Pixel* pixel = frame.row(y);
    std::uint8_t* mask = foreground.row(y);
    std::uint32_t count = 0;
    for (int x = 0; x < frame.width(); ++x) {
      const std::int32_t difference = static_cast<std::int32_t>(pixel[x]) - static_cast<std::int32_t>((cell[x] + 128) >> 8);
      const bool is_foreground = difference > threshold || difference < -threshold;
      mask[x] = is_foreground ? 255 : 0;
      count += is_foreground ? 1u : 0u;
    }
    result.foreground_pixels += count;
  }
  // Pass 2: the gated update.
  if (result.foreground_pixels > config_.max_foreground_pixels) return result;
  result.updated = true;
  const int shift = config_.update_shift;
  const std::int32_t half = shift > 0 ? std::int32_t{1} << (shift - 1) : 0;
  for (int y = 0; y < frame.height(); ++y) {
    std::uint32_t* cell = &cells_[index(0, y)];
    const Pixel* pixel = frame.row(y);
    for (int x = 0; x < frame.width(); ++x) {
      const std::int32_t delta = (static_cast<std::int32_t>(pixel[x]) << 8) - static_cast<std::int32_t>(cell[x]);
      // Round the step to nearest, ties away from zero, symmetrically for +delta and -delta.
      const std::int32_t step = delta >= 0 ? (delta + half) >> shift : -((-delta + half) >> shift);
      cell[x] = static_cast<std::uint32_t>(static_cast<std::int32_t>(cell[x]) + step);
    }
  }
  return result;
}

}  // namespace irloc
