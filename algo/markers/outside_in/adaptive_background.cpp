#include "algo/markers/outside_in/adaptive_background.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace irloc::outside_in {
namespace {
constexpr int kGainBins = 1024;  // Q8 gain in [0, 4)
constexpr std::size_t kHistogramCopies = 4;
constexpr std::size_t kCopyStride = kGainBins;
constexpr int kMinSampleLevel = 16;  // darker background pixels say little about a gain

const AdaptiveBackgroundConfig& checked(const AdaptiveBackgroundConfig& config) {
  const auto require = [](bool ok, const char* field, int value) {
    if (!ok) throw std::invalid_argument(std::string("adaptive background: ") + field + " " + std::to_string(value) + " out of range");
  };
  require(config.width >= 1, "width", config.width);
  require(config.height >= 1, "height", config.height);
  require(config.threshold >= 0 && config.threshold <= 255, "threshold", config.threshold);
  require(config.update_shift >= 0 && config.update_shift <= 15, "update_shift", config.update_shift);
  require(config.gate_radius >= 0 && config.gate_radius <= SquareMaskFilter::kMaxRadius, "gate_radius", config.gate_radius);
  require(config.absorb_frames >= 1 && config.absorb_frames <= 255, "absorb_frames", config.absorb_frames);
  require(config.still_levels >= 0 && config.still_levels <= 63, "still_levels", config.still_levels);
  require(config.still_radius >= 0 && config.still_radius <= SquareMaskFilter::kMaxRadius, "still_radius", config.still_radius);
  require(config.sample_step >= 1, "sample_step", config.sample_step);
  require(config.shadow_min_ratio_q8 >= 0 && config.shadow_min_ratio_q8 <= 256, "shadow_min_ratio_q8", config.shadow_min_ratio_q8);
  return config;
}

}  // namespace

AdaptiveBackground::AdaptiveBackground(const AdaptiveBackgroundConfig& config)
    : config_(checked(config)),
      cells_(static_cast<std::size_t>(config.width) * static_cast<std::size_t>(config.height)),
      previous_(cells_.size()),
      still_count_(cells_.size()),
      motion_(cells_.size()),
      protected_row_(static_cast<std::size_t>(config.width)),
      no_pixels_(static_cast<std::size_t>(config.width)),
      row_foreground_(static_cast<std::size_t>(config.height)),
      sample_histogram_(kHistogramCopies * kCopyStride),
      grow_foreground_(config.width, config.gate_radius, SquareMaskFilter::Operation::dilate),
      grow_motion_(config.width, config.still_radius, SquareMaskFilter::Operation::dilate) {}

void AdaptiveBackground::restart() {
  started_ = false;
  for (std::vector<std::uint8_t>* plane : {&previous_, &still_count_, &motion_}) {
    std::fill(plane->begin(), plane->end(), std::uint8_t{0});
  }
  std::fill(cells_.begin(), cells_.end(), std::uint16_t{0});
}

template <typename BinOf>
int AdaptiveBackground::sample_median(ImageView8 frame, BinOf bin_of) {
  // kHistogramCopies copies, a sample's copy by its count: nearly every sample falls in the same
  // few bins, and the increments of one histogram would wait on each other.
  std::fill(sample_histogram_.begin(), sample_histogram_.end(), 0u);
  std::uint32_t samples = 0;
  const int step = config_.sample_step;
  for (int y = step / 2; y < config_.height; y += step) {
    const std::uint8_t* row = frame.row(y);
    for (int x = step / 2; x < config_.width; x += step) {
      const int bin = bin_of(row[x], index(x, y));
      if (bin < 0) continue;
      ++sample_histogram_[(samples % kHistogramCopies) * kCopyStride + static_cast<std::size_t>(bin)];
      ++samples;
    }
  }
  std::uint32_t below = 0;
  for (int bin = 0; bin < kGainBins; ++bin) {
    for (std::size_t copy = 0; copy < kHistogramCopies; ++copy) {
      below += sample_histogram_[copy * kCopyStride + static_cast<std::size_t>(bin)];
    }
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

void AdaptiveBackground::mark_protected(const ProtectedRects& protect, int y) {
  std::fill(protected_row_.begin(), protected_row_.end(), std::uint8_t{0});
  for (int i = 0; i < protect.count; ++i) {
    const PixelRect& rect = protect.rects[static_cast<std::size_t>(i)];
    const int x_begin = std::max(rect.x_min, 0), x_end = std::min(rect.x_max + 1, config_.width);
    if (y >= rect.y_min && y <= rect.y_max && x_begin < x_end) {
      std::fill(protected_row_.begin() + x_begin, protected_row_.begin() + x_end, std::uint8_t{255});
    }
  }
}

void AdaptiveBackground::update_row(ImageView8 frame, ImageView8 foreground, ImageView8 motion,
                                    const ProtectedRects& protect, std::uint32_t foreground_near, int y,
                                    const background_rows::UpdateParams& update) {
  std::uint16_t* cell_row = cells_.data() + index(0, y);
  // Without foreground within the gate radius nothing is gated or counted: the grown masks are
  // not formed (their filters only keep their counts) and every cell follows the frame.
  if (foreground_near == 0) {
    grow_foreground_.skip_row(foreground, y);
    grow_motion_.skip_row(motion, y);
    background_rows::follow(frame.row(y), config_.width, update.update_shift, cell_row, row_of(still_count_, y));
    return;
  }
  const std::uint8_t* grown = grow_foreground_.row(foreground, y);
  // Grown motion only matters where the row has foreground (still counts); elsewhere none is read.
  const bool row_has_foreground = row_foreground_[static_cast<std::size_t>(y)] > 0;
  const std::uint8_t* motion_grown = no_pixels_.data();
  if (row_has_foreground) {
    motion_grown = grow_motion_.row(motion, y);
  } else {
    grow_motion_.skip_row(motion, y);
  }
  mark_protected(protect, y);
  background_rows::update(frame.row(y), foreground.row(y), motion.row(y), grown, motion_grown, protected_row_.data(),
                          config_.width, update, cell_row, row_of(still_count_, y));
}

BackgroundStep AdaptiveBackground::apply(ImageView8 frame, MutableImageView8 foreground, const ProtectedRects& protect) {
  BackgroundStep step;
  step.protected_dropped = protect.dropped;
  const int width = config_.width, height = config_.height;
  if (!started_) {
    for (int y = 0; y < height; ++y) {
      const std::uint8_t* in = frame.row(y);
      std::uint16_t* cell_row = cells_.data() + index(0, y);
      for (int x = 0; x < width; ++x) cell_row[x] = static_cast<std::uint16_t>(in[x] << 8);
      std::copy_n(in, width, row_of(previous_, y));
      std::fill_n(foreground.row(y), width, std::uint8_t{0});
    }
    started_ = true;
    return step;
  }
  const std::uint32_t gain_q8 = measure_gain_q8(frame);
  step.gain = gain_q8 / 256.0;
  step.light_change = gain_q8 < 252 || gain_q8 > 260;
  const background_rows::ClassifyParams classify{static_cast<std::uint16_t>(config_.threshold << 8),
                                                 static_cast<std::uint16_t>(config_.shadow_min_ratio_q8),
                                                 static_cast<std::uint8_t>(measure_still_levels(frame))};
  const background_rows::UpdateParams update{config_.update_shift, static_cast<std::uint8_t>(config_.absorb_frames)};
  const ImageView8 classified(foreground.data(), width, height, foreground.stride());
  const ImageView8 motion(motion_.data(), width, height);
  // Row y is updated once the rows its grown masks reach are classified (header, "One pass").
  const int gate = config_.gate_radius;
  const int lag = std::max(gate, config_.still_radius);
  std::uint32_t foreground_near = 0;  // foreground pixels in rows y - gate .. y + gate
  int rows_near = 0;                  // rows added to foreground_near
  for (int k = 0; k < height + lag; ++k) {
    if (k < height) {
      std::uint16_t* cell_row = cells_.data() + index(0, k);
      if (step.light_change) background_rows::rescale(cell_row, width, gain_q8);
      row_foreground_[static_cast<std::size_t>(k)] = background_rows::classify(
          frame.row(k), cell_row, row_of(previous_, k), width, classify, foreground.row(k), row_of(motion_, k));
      step.foreground_pixels += row_foreground_[static_cast<std::size_t>(k)];
    }
    const int y = k - lag;
    if (y < 0) continue;
    for (; rows_near <= std::min(y + gate, height - 1); ++rows_near) {
      foreground_near += row_foreground_[static_cast<std::size_t>(rows_near)];
    }
    if (y - gate - 1 >= 0) foreground_near -= row_foreground_[static_cast<std::size_t>(y - gate - 1)];
    update_row(frame, classified, motion, protect, foreground_near, y, update);
  }
  return step;
}

}  // namespace irloc::outside_in
