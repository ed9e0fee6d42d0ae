#pragma once
// The background of a fixed camera, learned while things (the robot, people) may be in view, and
// robust to global light changes. 8-bit frames.
//
// Per frame:
//  1. Global light: the gain g between frame and background is the median, over a grid of
//     sample pixels, of frame / background (a robust statistic: movers cover far less than half
//     of the view). When g departs from 1 by more than 1/64 (a lamp, the camera's auto-exposure),
//     the whole background is rescaled by g before differencing, so the change is absorbed in the
//     frame it happens, with no burst of foreground.
//  2. Foreground: |frame - background| > threshold, except a pixel darker than the background by a
//     factor in [shadow_min_ratio, 1): a shadow on the floor (the robot's contact shadow, a
//     person's), whose shape would bias the robot's fit. Objects must differ from the floor by
//     more than that (docs/outside_in.md).
//  3. Gated update, per pixel: a pixel that is not foreground follows the frame, by
//     2^-update_shift per frame, unless it lies within `gate_radius` pixels of foreground and
//     either changed since the last frame (a mover's edge arriving) or lies in a protected
//     rectangle (the tracked robot: its faces as bright as the floor or in its shadow range are
//     not foreground, and must not become background). Elsewhere, floor beside foreground keeps
//     following the light: frozen there, a drifting sun patch grew into a ghost merged with a
//     robot that turned in place (each frozen pixel it turned foreground froze its neighbours).
//  4. Robust start: a pixel that stays foreground while nothing within `still_radius` pixels of
//     it changes, for `absorb_frames` frames (what was behind a robot that was in view when the
//     model started, a moved chair), is taken into the background, unless it lies in a
//     protected rectangle (the tracked robot, which may stand still; a mover half in view). The radius keeps the
//     uniform inside of a moving robot, whose own pixels do not change, out of the background.
//     "Changes" are those above the sensor noise: |frame - previous| over 4.5 sigma of the
//     frame-to-frame noise measured on the sample grid (its median), within [still_levels,
//     4 still_levels]; at a fixed still_levels noisy pixels would be "moving" in every
//     still_radius square and nothing would ever be absorbed.
//
// Fixed point: the background is Q8.8 (uint16 raw = grey * 256); the gain is Q8 (raw = g * 256,
// histogram of 1024 bins over [0, 4)); the rescale is raw = (raw * gain_q8 + 128) >> 8, saturated;
// the shadow ratio is Q8. The rescale is 32-bit lane arithmetic, the motion test 8-bit, every other
// per-pixel step 16-bit (background_rows.hpp).
//
// One pass over the sample grid (both medians), then one over the rows: row k is rescaled and
// classified (foreground, motion), and row y = k - max(gate_radius, still_radius) is updated, its grown
// foreground and grown motion taken from running square dilations (SquareMaskFilter) of the rows
// classified so far. Each pixel's state is read and written once per frame; the work per pixel
// does not depend on the radii. A row with no foreground within gate_radius rows is only followed
// (nothing there is gated or counted), and so is each vector of pixels in other rows whose grown
// foreground is 0; the grown masks are formed only for the rows that read them: most of a frame
// costs the classify pass and the follow.
#include <array>
#include <cstdint>
#include <vector>
#include "algo/core/image_view.hpp"
#include "algo/kernels/square_mask_filter.hpp"
#include "algo/markers/outside_in/background_rows.hpp"

namespace irloc::outside_in {

// The ranges after each field are checked by AdaptiveBackground's constructor.
struct AdaptiveBackgroundConfig {
  int width = 0;
  int height = 0;
  int threshold = 24;          // 0..255: grey levels of |frame - background| that are foreground
  int update_shift = 5;        // 0..15: background follows a still scene by 1/32 per frame
  int gate_radius = 4;         // 0..127 px around foreground where a pixel that changed is not updated
  int absorb_frames = 10;      // 1..255 still foreground frames before it is background
  int still_levels = 6;        // 0..63: |frame - previous frame| up to this is always "still" (see 4.)
  int still_radius = 12;       // 0..127 px around a pixel that must be still too
  int sample_step = 4;         // >= 1: gain samples on a grid of this pitch
  int shadow_min_ratio_q8 = 128;  // 0..256: frame / background >= this (Q8: 128 = 0.5) and < 1 is shadow
};

struct PixelRect {
  int x_min = 0, y_min = 0, x_max = -1, y_max = -1;  // inclusive; empty when x_max < x_min
  bool contains(int x, int y) const { return x >= x_min && x <= x_max && y >= y_min && y <= y_max; }
};

// Where foreground is never absorbed: a bounded set of rectangles. Further ones are dropped and
// counted (safe: what they would have protected is only absorbed sooner).
struct ProtectedRects {
  static constexpr int kCapacity = 8;
  std::array<PixelRect, kCapacity> rects;
  int count = 0;
  std::uint32_t dropped = 0;
  bool add(const PixelRect& rect) {
    if (count == kCapacity) {
      ++dropped;
      return false;
    }
    rects[static_cast<std::size_t>(count++)] = rect;
    return true;
  }
  bool contains(int x, int y) const {
    for (int i = 0; i < count; ++i)
      if (rects[static_cast<std::size_t>(i)].contains(x, y)) return true;
    return false;
  }
};

struct BackgroundStep {
  double gain = 1;            // the global light change measured (frame / background)
  bool light_change = false;  // the background was rescaled by it
  std::uint32_t foreground_pixels = 0;
  std::uint32_t protected_dropped = 0;  // rectangles beyond ProtectedRects' capacity, this frame
};

class AdaptiveBackground {
 public:
  // Allocates every buffer here; apply() allocates nothing. A field out of its range (above) or a
  // size below 1 x 1: std::invalid_argument naming it.
  explicit AdaptiveBackground(const AdaptiveBackgroundConfig& config);

  bool started() const { return started_; }
  // Forgets the background: the next frame starts it again, as for a model just made.
  void restart();
  // foreground = 255 where the frame differs from the background, else 0 (same size as the
  // frame). The first frame is taken as the background and has no foreground.
  BackgroundStep apply(ImageView8 frame, MutableImageView8 foreground, const ProtectedRects& protect);

  // Still foreground frames before absorption (the config's absorb_frames, header 4.), for a
  // caller that keeps it a time as the frame rate is measured; 1..255, else std::invalid_argument.
  void set_absorb_frames(int frames);
  int absorb_frames() const { return config_.absorb_frames; }

  // Background grey level at (x, y), rounded; and exactly, Q8.8.
  int value_at(int x, int y) const { return (cells_[index(x, y)] + 128) >> 8; }
  std::uint16_t value_q8_8_at(int x, int y) const { return cells_[index(x, y)]; }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(config_.width) + static_cast<std::size_t>(x);
  }
  struct SampleMeasures {
    std::uint32_t gain_q8 = 256;
    int still_levels = 0;
  };
  // The global gain and the still levels (header, 1. and 4.) from the sample grid, in one pass
  // that reads each sample's pixel, background cell and previous pixel once.
  SampleMeasures measure_samples(ImageView8 frame);
  // The protected rectangles' pixels of row y as 255 in protected_row_.
  void mark_protected(const ProtectedRects& protect, int y);
  // The gated update of row y (its grown masks' filters take their turn for row y); foreground_near:
  // the foreground pixels of rows y - gate_radius .. y + gate_radius.
  void update_row(ImageView8 frame, ImageView8 foreground, ImageView8 motion, const ProtectedRects& protect,
                  std::uint32_t foreground_near, int y, const background_rows::UpdateParams& update);
  std::uint8_t* row_of(std::vector<std::uint8_t>& plane, int y) { return plane.data() + index(0, y); }

  AdaptiveBackgroundConfig config_;
  bool started_ = false;
  std::vector<std::uint16_t> cells_;          // Q8.8 background
  std::vector<std::uint8_t> previous_;        // the last frame
  std::vector<std::uint8_t> still_count_;     // frames a pixel has been still foreground
  std::vector<std::uint8_t> motion_;          // 255 where the frame changed since the last one
  std::vector<std::uint8_t> protected_row_;   // 255 in a protected rectangle, for the row updated
  std::vector<std::uint8_t> no_pixels_;       // a row of 0: the grown motion of a row without foreground
  std::vector<std::uint32_t> row_foreground_;  // this frame's foreground pixels per row
  std::vector<std::uint32_t> gain_histogram_;   // of the gain samples (4 copies)
  std::vector<std::uint32_t> still_histogram_;  // of the still samples, |frame - previous| (4 copies)
  SquareMaskFilter grow_foreground_;          // by gate_radius
  SquareMaskFilter grow_motion_;              // by still_radius
};

}  // namespace irloc::outside_in
