// The adaptive background's one-pass vector kernels against a plain reference: the per-pixel
// rules of adaptive_background.hpp written out pixel by pixel, in three separate passes, as the
// model was first built (foreground and motion; the square dilations; the gated update), with
// the plain dilation of tests/kernels/reference_kernels. Random frame sequences of every kind
// the model meets: noise, movers, objects that stop and are absorbed, light steps, saturated
// frames, protected rectangles partly outside the image and beyond capacity, odd widths and
// padded rows; the foreground, the step's figures and every background cell (Q8.8) must be equal.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "algo/markers/outside_in/adaptive_background.hpp"
#include "tests/kernels/reference_kernels.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::outside_in {
namespace {

class PlainBackground {
 public:
  explicit PlainBackground(const AdaptiveBackgroundConfig& config)
      : c_(config), n_(static_cast<std::size_t>(config.width) * static_cast<std::size_t>(config.height)),
        cells_(n_), previous_(n_), still_(n_), motion_(n_), grown_(n_), motion_grown_(n_) {}

  std::uint16_t cell(int x, int y) const { return cells_[at(x, y)]; }
  void restart() { *this = PlainBackground(c_); }

  BackgroundStep apply(ImageView8 frame, MutableImageView8 foreground, const ProtectedRects& protect) {
    BackgroundStep step;
    step.protected_dropped = protect.dropped;
    const int w = c_.width, h = c_.height;
    if (!started_) {
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          cells_[at(x, y)] = static_cast<std::uint16_t>(frame.at(x, y) << 8);
          previous_[at(x, y)] = frame.at(x, y);
          foreground.at(x, y) = 0;
        }
      started_ = true;
      return step;
    }
    // The gain: the median over the sample grid of frame / background (Q8, 1024 bins).
    const int gain = median_bin([&](int x, int y) {
      const std::uint32_t background = cells_[at(x, y)];
      if (background < (16u << 8)) return -1;
      return static_cast<int>(std::min<std::uint32_t>((std::uint32_t{frame.at(x, y)} << 16) / background, 1023));
    });
    const std::uint32_t gain_q8 = gain < 0 ? 256 : static_cast<std::uint32_t>(gain);
    step.gain = gain_q8 / 256.0;
    if (gain_q8 < 252 || gain_q8 > 260) {
      for (std::uint16_t& cell : cells_)
        cell = static_cast<std::uint16_t>(std::min<std::uint32_t>((cell * gain_q8 + 128) >> 8, 0xFFFF));
      step.light_change = true;
    }
    // The noise: 4.5 sigma of the frame-to-frame difference from its median on the grid.
    const int still_median = std::max(0, median_bin([&](int x, int y) {
      return std::abs(static_cast<int>(frame.at(x, y)) - static_cast<int>(previous_[at(x, y)]));
    }));
    const int still_levels = std::clamp((still_median * 20 + 2) / 3, c_.still_levels, 4 * c_.still_levels);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const int pixel = frame.at(x, y) << 8, background = cells_[at(x, y)];
        const bool shadow = pixel < background && (pixel << 8) >= c_.shadow_min_ratio_q8 * background;
        const bool moving = std::abs(pixel - background) > (c_.threshold << 8) && !shadow;
        foreground.at(x, y) = moving ? 255 : 0;
        step.foreground_pixels += moving;
        motion_[at(x, y)] = std::abs(frame.at(x, y) - previous_[at(x, y)]) > still_levels ? 255 : 0;
      }
    reference::dilate(ImageView8(motion_.data(), w, h), {ElementShape::square, c_.still_radius},
                      MutableImageView8(motion_grown_.data(), w, h));
    reference::dilate(foreground, {ElementShape::square, c_.gate_radius}, MutableImageView8(grown_.data(), w, h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = at(x, y);
        const int target = frame.at(x, y) << 8;
        const bool moving = foreground.at(x, y) != 0;
        const bool gated = grown_[i] != 0 && (motion_[i] != 0 || protect.contains(x, y));
        if (!moving && !gated) {
          const int delta = target - cells_[i], step_size = 1 << c_.update_shift;
          const int change = delta >= 0 ? (delta + step_size - 1) / step_size : -((-delta + step_size - 1) / step_size);
          cells_[i] = static_cast<std::uint16_t>(cells_[i] + change);
          still_[i] = 0;
        } else if (moving && motion_grown_[i] == 0 && !protect.contains(x, y)) {
          if (++still_[i] >= c_.absorb_frames) {
            cells_[i] = static_cast<std::uint16_t>(target);
            still_[i] = 0;
          }
        } else {
          still_[i] = 0;
        }
        previous_[i] = frame.at(x, y);
      }
    return step;
  }

 private:
  std::size_t at(int x, int y) const { return static_cast<std::size_t>(y) * static_cast<std::size_t>(c_.width) + static_cast<std::size_t>(x); }
  template <typename BinOf>
  int median_bin(BinOf bin_of) const {
    std::vector<int> bins;
    for (int y = c_.sample_step / 2; y < c_.height; y += c_.sample_step)
      for (int x = c_.sample_step / 2; x < c_.width; x += c_.sample_step)
        if (const int bin = bin_of(x, y); bin >= 0) bins.push_back(bin);
    if (bins.empty()) return -1;
    std::sort(bins.begin(), bins.end());
    return bins[(bins.size() + 1) / 2 - 1];  // the least bin with at least half the samples at or below it
  }

  AdaptiveBackgroundConfig c_;
  std::size_t n_;
  bool started_ = false;
  std::vector<std::uint16_t> cells_;
  std::vector<std::uint8_t> previous_, still_, motion_, grown_, motion_grown_;
};

// A floor with texture, dark and saturated patches; each frame adds sensor noise, movers (some of
// which stop for a while, to be absorbed), light steps; now and then a frame all black or all white.
class FrameSequence {
 public:
  FrameSequence(int width, int height, unsigned seed) : w_(width), h_(height), rng_(seed), floor_(area()), frame_(area()) {
    std::uniform_int_distribution<int> grey(0, 255);
    for (std::uint8_t& p : floor_) p = static_cast<std::uint8_t>(grey(rng_));
    paint(floor_, 0);    // a black patch
    paint(floor_, 255);  // a saturated one
  }

  const std::vector<std::uint8_t>& next(int i) {
    std::normal_distribution<double> noise(0, 0.5 + roll(0, 3));
    const double gain = i % 11 == 7 ? 0.6 : i % 13 == 5 ? 1.5 : 1.0;
    for (std::size_t k = 0; k < frame_.size(); ++k)
      frame_[k] = static_cast<std::uint8_t>(std::lround(std::clamp(floor_[k] * gain + noise(rng_), 0.0, 255.0)));
    if (i % 9 == 4) std::fill(frame_.begin(), frame_.end(), i % 2 ? 255 : 0);
    for (int mover = 0; mover < 3; ++mover) paint(frame_, roll(0, 255));
    // An object put down at frame 5 and left: absorbed after absorb_frames still frames.
    if (i >= 5) paint_at(frame_, w_ / 3, h_ / 3, std::max(3, w_ / 5), std::max(3, h_ / 5), 200);
    return frame_;
  }

  ProtectedRects protect() {
    ProtectedRects rects;
    const int count = roll(0, 10);  // up to two beyond capacity
    for (int k = 0; k < count; ++k) {
      const int x = roll(-5, w_ + 2), y = roll(-5, h_ + 2);
      rects.add({x, y, x + roll(-2, w_ / 2), y + roll(-2, h_ / 2)});  // some empty, some past the edge
    }
    return rects;
  }

 private:
  std::size_t area() const { return static_cast<std::size_t>(w_) * static_cast<std::size_t>(h_); }
  int roll(int low, int high) { return std::uniform_int_distribution<int>(low, high)(rng_); }
  void paint(std::vector<std::uint8_t>& image, int value) {
    paint_at(image, roll(-4, w_ - 1), roll(-4, h_ - 1), roll(1, std::max(1, w_ / 3)), roll(1, std::max(1, h_ / 3)), value);
  }
  void paint_at(std::vector<std::uint8_t>& image, int x0, int y0, int w, int h, int value) {
    for (int y = std::max(0, y0); y < std::min(h_, y0 + h); ++y)
      for (int x = std::max(0, x0); x < std::min(w_, x0 + w); ++x) image[static_cast<std::size_t>(y) * w_ + x] = static_cast<std::uint8_t>(value);
  }

  int w_, h_;
  std::mt19937 rng_;
  std::vector<std::uint8_t> floor_, frame_;
};

void expect_same_as_plain(const AdaptiveBackgroundConfig& config, int frames, unsigned seed) {
  SCOPED_TRACE(testing::Message() << config.width << "x" << config.height << " threshold " << config.threshold
                                  << " shift " << config.update_shift << " gate " << config.gate_radius << " absorb "
                                  << config.absorb_frames << " still " << config.still_levels << "/"
                                  << config.still_radius << " step " << config.sample_step << " shadow "
                                  << config.shadow_min_ratio_q8 << " seed " << seed);
  AdaptiveBackground fast(config);
  PlainBackground plain(config);
  FrameSequence sequence(config.width, config.height, seed);
  // The foreground image has padded rows (stride above the width): the padding stays untouched.
  const int stride = config.width + 5;
  std::vector<std::uint8_t> fast_out(static_cast<std::size_t>(stride) * config.height, 0x5A);
  std::vector<std::uint8_t> plain_out(fast_out);
  for (int i = 0; i < frames; ++i) {
    if (i == frames / 2) {  // forget and start again, both
      fast.restart();
      plain.restart();
    }
    const std::vector<std::uint8_t>& frame = sequence.next(i);
    const ImageView8 view(frame.data(), config.width, config.height);
    const ProtectedRects protect = sequence.protect();
    const BackgroundStep a = fast.apply(view, MutableImageView8(fast_out.data(), config.width, config.height, stride), protect);
    const BackgroundStep b = plain.apply(view, MutableImageView8(plain_out.data(), config.width, config.height, stride), protect);
    ASSERT_EQ(a.gain, b.gain) << "frame " << i;
    ASSERT_EQ(a.light_change, b.light_change) << "frame " << i;
    ASSERT_EQ(a.foreground_pixels, b.foreground_pixels) << "frame " << i;
    ASSERT_EQ(a.protected_dropped, b.protected_dropped) << "frame " << i;
    ASSERT_EQ(fast_out, plain_out) << "frame " << i;
    for (int y = 0; y < config.height; ++y) {
      int x = 0;
      while (x < config.width && fast.value_q8_8_at(x, y) == plain.cell(x, y)) ++x;
      ASSERT_EQ(x, config.width) << "frame " << i << ": background at " << x << "," << y << " is "
                                 << fast.value_q8_8_at(x, y) << ", the reference's " << plain.cell(x, y);
    }
  }
}

TEST(AdaptiveBackground, EqualsThePlainReferenceOnRandomFrames) {
  // The defaults at widths with and without a partial last vector, and a single column.
  for (const auto& [width, height] : {std::pair{67, 45}, std::pair{96, 40}, std::pair{1, 30}, std::pair{33, 1}}) {
    AdaptiveBackgroundConfig config;
    config.width = width;
    config.height = height;
    expect_same_as_plain(config, 30, static_cast<unsigned>(width * 7 + height));
  }
  // Every setting at its range's ends and between: each value in at least two of the trials, the
  // settings' values combined differently in each.
  for (int trial = 0; trial < 8; ++trial) {
    int field = 0;
    const auto pick = [&](std::initializer_list<int> values) {
      const int size = static_cast<int>(values.size());
      return values.begin()[(trial + field++ + trial / size) % size];
    };
    AdaptiveBackgroundConfig config;
    config.width = pick({17, 40, 67});
    config.height = pick({9, 31});
    config.threshold = pick({0, 1, 24, 255});
    config.update_shift = pick({0, 1, 5, 15});
    config.gate_radius = pick({0, 1, 4, 9});
    config.absorb_frames = pick({1, 3, 10, 255});
    config.still_levels = pick({0, 6, 63});
    config.still_radius = pick({0, 2, 12, 20});
    config.sample_step = pick({1, 4, 7});
    config.shadow_min_ratio_q8 = pick({0, 128, 255, 256});
    expect_same_as_plain(config, 24, static_cast<unsigned>(trial));
  }
}

TEST(AdaptiveBackground, RefusesSettingsOutOfRange) {
  const auto with = [](auto change) {
    AdaptiveBackgroundConfig config;
    config.width = 64;
    config.height = 48;
    change(config);
    return config;
  };
  EXPECT_NO_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig&) {})));
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.width = 0; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.threshold = 256; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.update_shift = 16; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.gate_radius = 128; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.absorb_frames = 0; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.still_levels = 64; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.still_radius = -1; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.sample_step = 0; })), std::invalid_argument);
  EXPECT_THROW(AdaptiveBackground(with([](AdaptiveBackgroundConfig& c) { c.shadow_min_ratio_q8 = 257; })), std::invalid_argument);
}

TEST(AdaptiveBackground, AllocatesNothingPerFrame) {
  AdaptiveBackground background(AdaptiveBackgroundConfig{131, 70});
  FrameSequence sequence(131, 70, 3);
  std::vector<std::uint8_t> foreground(131 * 70);
  const MutableImageView8 mask(foreground.data(), 131, 70);
  background.apply(ImageView8(sequence.next(0).data(), 131, 70), mask, {});
  const std::vector<std::uint8_t> frame = sequence.next(1);
  test::AllocationCounter counter;
  for (int i = 0; i < 3; ++i) background.apply(ImageView8(frame.data(), 131, 70), mask, {});
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace irloc::outside_in
