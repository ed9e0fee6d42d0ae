#include "algo/outside_in/adaptive_background.hpp"

#include <algorithm>
#include <cstdlib>

namespace irloc {
namespace {
constexpr int kGainBins = 1024;  // Q8 gain in [0, 4)
constexpr int kMinSampleLevel = 16;  // darker background pixels say little about a gain
}  // namespace

AdaptiveBackground::AdaptiveBackground(const AdaptiveBackgroundConfig& config)
    : config_(config),
      cells_(static_cast<std::size_t>(config.width) * config.height),
      previous_(cells_.size()),
      still_count_(cells_.size()),
      grown_(cells_.size()),
      motion_(cells_.size()),
      motion_grown_(cells_.size()),
      sample_histogram_(kGainBins),
      morphology_(config.width) {}

void AdaptiveBackground::restart() {
  started_ = false;
  for (std::vector<std::uint8_t>* plane : {&previous_, &still_count_, &grown_, &motion_, &motion_grown_}) {
    std::fill(plane->begin(), plane->end(), std::uint8_t{0});
  }
  std::fill(cells_.begin(), cells_.end(), std::uint16_t{0});
}

template <typename BinOf>
int AdaptiveBackground::sample_median(ImageView8 frame, BinOf bin_of) {
  std::fill(sample_histogram_.begin(), sample_histogram_.end(), 0u);
  std::uint32_t samples = 0;
  const int step = config_.sample_step;
  for (int y = step / 2; y < config_.height; y += step) {
    const std::uint8_t* row = frame.row(y);
    for (int x = step / 2; x < config_.width; x += step) {
      const int bin = bin_of(row[x], index(x, y));
      if (bin < 0) continue;
      ++sample_histogram_[static_cast<std::size_t>(bin)];
      ++samples;
    }
  }
  std::uint32_t below = 0;
  for (int bin = 0; bin < kGainBins; ++bin) {
    below += sample_histogram_[static_cast<std::size_t>(bin)];
    if (samples > 0 && 2 * below >= samples) return bin;
  }
  return -1;
}

std::uint32_t AdaptiveBackground::measure_gain_q8(ImageView8 frame) {
  const int median = sample_median(frame, [&](std::uint8_t pixel, std::size_t i) {
    const std::uint32_t background = cells_[i];  // Q8.8
    if (background < (kMinSampleLevel << 8)) return -1;
    // frame / background in Q8: (frame << 16) / background.
    const std::uint32_t ratio = (static_cast<std::uint32_t>(pixel) << 16) / background;
    return static_cast<int>(std::min<std::uint32_t>(ratio, kGainBins - 1));
  });
  return median < 0 ? 256 : static_cast<std::uint32_t>(median);
}

int AdaptiveBackground::measure_still_levels(ImageView8 frame) {
  // The median |frame - previous| over the sample grid is 0.674 sigma_d for sensor noise of
  // standard deviation sigma_d / sqrt(2) per frame; movers cover far less than half the grid.
  const int median = std::max(0, sample_median(frame, [&](std::uint8_t pixel, std::size_t i) {
    return std::abs(static_cast<int>(pixel) - static_cast<int>(previous_[i]));
  }));
  // 4.5 sigma_d = 4.5 / 0.674 median: about one pixel in 150 000 is noise above it.
  const int levels = (median * 20 + 2) / 3;
  return std::clamp(levels, config_.still_levels, 4 * config_.still_levels);
}

void AdaptiveBackground::rescale(std::uint32_t gain_q8) {
  for (std::uint16_t& cell : cells_)
    cell = static_cast<std::uint16_t>(std::min<std::uint32_t>((cell * gain_q8 + 128) >> 8, 0xFFFF));
}

BackgroundStep AdaptiveBackground::apply(ImageView8 frame, MutableImageView8 foreground, const ProtectedRects& protect) {
  BackgroundStep step;
  step.protected_dropped = protect.dropped;
  const int width = config_.width, height = config_.height;
  if (!started_) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        cells_[index(x, y)] = static_cast<std::uint16_t>(frame.at(x, y) << 8);
        previous_[index(x, y)] = frame.at(x, y);
        foreground.at(x, y) = 0;
      }
    started_ = true;
    return step;
  }
  const std::uint32_t gain_q8 = measure_gain_q8(frame);
  step.gain = gain_q8 / 256.0;
  if (gain_q8 < 252 || gain_q8 > 260) {
    rescale(gain_q8);
    step.light_change = true;
  }
  const int threshold = config_.threshold << 8;
  const int still_levels = measure_still_levels(frame);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = frame.row(y);
    std::uint8_t* out = foreground.row(y);
    for (int x = 0; x < width; ++x) {
      const int pixel = static_cast<int>(in[x]) << 8, background = cells_[index(x, y)];
      // Shadow: pixel / background in [shadow_min_ratio, 1), i.e. pixel << 8 >= ratio_q8 * background.
      const bool shadow = pixel < background && (pixel << 8) >= config_.shadow_min_ratio_q8 * background;
      const bool moving = std::abs(pixel - background) > threshold && !shadow;
      out[x] = moving ? 255 : 0;
      step.foreground_pixels += moving;
      motion_[index(x, y)] = std::abs(static_cast<int>(in[x]) - static_cast<int>(previous_[index(x, y)])) > still_levels ? 255 : 0;
    }
  }
  morphology_.dilate(ImageView8(motion_.data(), width, height), {ElementShape::square, config_.still_radius},
                     MutableImageView8(motion_grown_.data(), width, height));
  morphology_.dilate(foreground, {ElementShape::square, config_.gate_radius},
                     MutableImageView8(grown_.data(), width, height));
  const int shift = config_.update_shift;
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* in = frame.row(y);
    const std::uint8_t* moving = foreground.row(y);
    for (int x = 0; x < width; ++x) {
      const std::size_t i = index(x, y);
      const int target = static_cast<int>(in[x]) << 8;
      const bool gated = grown_[i] != 0 && (motion_[i] != 0 || protect.contains(x, y));
      if (!moving[x] && !gated) {  // see the header's step 3
        // Round the step away from zero so a still scene converges to the grey level.
        const int delta = target - static_cast<int>(cells_[i]);
        const int change = delta >= 0 ? (delta + (1 << shift) - 1) >> shift : -((-delta + (1 << shift) - 1) >> shift);
        cells_[i] = static_cast<std::uint16_t>(static_cast<int>(cells_[i]) + change);
        still_count_[i] = 0;
      } else if (moving[x] && motion_grown_[i] == 0 && !protect.contains(x, y)) {
        if (++still_count_[i] >= config_.absorb_frames) {
          cells_[i] = static_cast<std::uint16_t>(target);
          still_count_[i] = 0;
        }
      } else {
        still_count_[i] = 0;
      }
      previous_[i] = in[x];
    }
  }
  return step;
}

}  // namespace irloc
