#include "algo/markers/outside_in/adaptive_background.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace irloc::outside_in {
namespace {
constexpr int kGainBins = 1024;  // Q8 gain in [0, 4)
constexpr int kStillBins = 256;  // |frame - previous|
// Each histogram in this many copies, a sample's copy by its place in the row: nearly every sample
// falls in the same few bins, and the increments of one histogram would wait on each other.
constexpr int kHistogramCopies = 4;
constexpr int kMinSampleLevel = 16;  // darker background pixels say little about a gain

void require_absorb_frames(int frames) {
  if (frames < 1 || frames > 255)
    throw std::invalid_argument("adaptive background: absorb_frames " + std::to_string(frames) + " out of range");
}

const AdaptiveBackgroundConfig& checked(const AdaptiveBackgroundConfig& config) {
  const auto require = [](bool ok, const char* field, int value) {
    if (!ok) throw std::invalid_argument(std::string("adaptive background: ") + field + " " + std::to_string(value) + " out of range");
  };
  require(config.width >= 1, "width", config.width);
  require(config.height >= 1, "height", config.height);
  require(config.threshold >= 0 && config.threshold <= 255, "threshold", config.threshold);
  require(config.update_shift >= 0 && config.update_shift <= 15, "update_shift", config.update_shift);
  require(config.gate_radius >= 0 && config.gate_radius <= SquareMaskFilter::kMaxRadius, "gate_radius", config.gate_radius);
  require_absorb_frames(config.absorb_frames);
  require(config.still_levels >= 0 && config.still_levels <= 63, "still_levels", config.still_levels);
  require(config.still_radius >= 0 && config.still_radius <= SquareMaskFilter::kMaxRadius, "still_radius", config.still_radius);
  require(config.sample_step >= 1, "sample_step", config.sample_step);
  require(config.shadow_min_ratio_q8 >= 0 && config.shadow_min_ratio_q8 <= 256, "shadow_min_ratio_q8", config.shadow_min_ratio_q8);
  return config;
}

// The median bin of a histogram of `bins` bins in kHistogramCopies copies holding `samples` in
// all; -1 if it holds none.
int median_bin(const std::vector<std::uint32_t>& histogram, int bins, std::uint32_t samples) {
  std::uint32_t below = 0;
  for (int bin = 0; bin < bins; ++bin) {
    for (int copy = 0; copy < kHistogramCopies; ++copy) below += histogram[static_cast<std::size_t>(copy * bins + bin)];
    if (samples > 0 && 2 * below >= samples) return bin;
  }
  return -1;
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
      gain_histogram_(kHistogramCopies * kGainBins),
      still_histogram_(kHistogramCopies * kStillBins),
      grow_foreground_(config.width, config.gate_radius, SquareMaskFilter::Operation::dilate),
      grow_motion_(config.width, config.still_radius, SquareMaskFilter::Operation::dilate) {}

void AdaptiveBackground::set_absorb_frames(int frames) {
  require_absorb_frames(frames);
  config_.absorb_frames = frames;
}

void AdaptiveBackground::restart() {
  started_ = false;
  for (std::vector<std::uint8_t>* plane : {&previous_, &still_count_, &motion_}) {
    std::fill(plane->begin(), plane->end(), std::uint8_t{0});
  }
  std::fill(cells_.begin(), cells_.end(), std::uint16_t{0});
}

AdaptiveBackground::SampleMeasures AdaptiveBackground::measure_samples(ImageView8 frame) {
  std::fill(gain_histogram_.begin(), gain_histogram_.end(), 0u);
  std::fill(still_histogram_.begin(), still_histogram_.end(), 0u);
  std::uint32_t gain_samples = 0, still_samples = 0;
  const int step = config_.sample_step;
  for (int y = step / 2; y < config_.height; y += step) {
    const std::uint8_t* row = frame.row(y);
    const std::uint16_t* cell_row = cells_.data() + index(0, y);
    const std::uint8_t* previous_row = row_of(previous_, y);
    const auto sample = [&](int x, int copy) {
      const int pixel = row[x];
      ++still_histogram_[static_cast<std::size_t>(copy * kStillBins + std::abs(pixel - previous_row[x]))];
      ++still_samples;
      // frame / background in Q8: (frame << 16) / background.
      const std::uint32_t background = cell_row[x];  // Q8.8
      if (background < (kMinSampleLevel << 8)) return;
      const std::uint32_t ratio = (static_cast<std::uint32_t>(pixel) << 16) / background;
      ++gain_histogram_[static_cast<std::size_t>(copy * kGainBins) + std::min<std::uint32_t>(ratio, kGainBins - 1)];
      ++gain_samples;
    };
    int x = step / 2;
    for (; x + 3 * step < config_.width; x += 4 * step) {
      for (int copy = 0; copy < kHistogramCopies; ++copy) sample(x + copy * step, copy);
    }
    for (; x < config_.width; x += step) sample(x, 0);
  }
  SampleMeasures measures;
  const int gain_median = median_bin(gain_histogram_, kGainBins, gain_samples);
  if (gain_median >= 0) measures.gain_q8 = static_cast<std::uint32_t>(gain_median);
  // The median |frame - previous| over the sample grid is 0.674 sigma_d for sensor noise of
  // standard deviation sigma_d / sqrt(2) per frame; movers cover far less than half the grid.
  const int still_median = std::max(0, median_bin(still_histogram_, kStillBins, still_samples));
  // 4.5 sigma_d = 4.5 / 0.674 median: about one pixel in 150 000 is noise above it.
  const int levels = (still_median * 20 + 2) / 3;
  measures.still_levels = std::clamp(levels, config_.still_levels, 4 * config_.still_levels);
  return measures;
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
  const SampleMeasures measures = measure_samples(frame);
  const std::uint32_t gain_q8 = measures.gain_q8;
  step.gain = gain_q8 / 256.0;
  step.light_change = gain_q8 < 252 || gain_q8 > 260;
  const background_rows::ClassifyParams classify{static_cast<std::uint16_t>(config_.threshold << 8),
                                                 static_cast<std::uint16_t>(config_.shadow_min_ratio_q8),
                                                 static_cast<std::uint8_t>(measures.still_levels)};
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
