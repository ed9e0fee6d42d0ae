#pragma once
// Background model for a fixed camera: a per-pixel running average in fixed point, whose update is
// gated as in surveillance-camera practice: the background is renewed only from frames whose
// foreground is small, so a robot, a person or a marker parked in view does not burn into it.
//
// Storage: Q16.8 per pixel (uint32 raw = value * 256) for 8- or 16-bit frames. Update with
// alpha = 2^-update_shift: bg += ((frame << 8) - bg) * alpha, the step rounded to nearest with ties
// away from zero (so the model converges to within 2^(update_shift - 9) grey levels of a
// constant scene; update_shift 0 replaces the background outright). update_shift <= 8.

#include <cstdint>
#include <vector>

#include "algo/core/image_view.hpp"

namespace irloc {

struct BackgroundConfig {
  int width = 0;
  int height = 0;
  int update_shift = 4;                   // alpha = 1/16
  std::uint32_t foreground_threshold = 16;  // |frame - background| > this is foreground, grey levels
  std::uint32_t max_foreground_pixels = 0;  // gate: update only if the foreground is at most this
};

struct BackgroundResult {
  std::uint32_t foreground_pixels = 0;
  bool updated = false;  // the gate let this frame into the background
};

class BackgroundModel {
 public:
  // Allocates width x height Q16.8 cells here; the model is empty (all 0) until reset().
  explicit BackgroundModel(const BackgroundConfig& config);

  // Takes a frame as the whole background.
  void reset(ImageView8 frame);
  void reset(ImageView16 frame);

  // foreground(x, y) = 255 where |frame - background| > foreground_threshold (background rounded
  // to whole grey levels), else 0; then, if the foreground count passes the gate, the running
  // average takes the frame in. frame and foreground have the configured size.
  BackgroundResult apply(ImageView8 frame, MutableImageView8 foreground);
  BackgroundResult apply(ImageView16 frame, MutableImageView8 foreground);

  // The background at (x, y): Q16.8 raw, and rounded to a whole grey level.
  std::uint32_t raw_at(int x, int y) const { return cells_[index(x, y)]; }
  std::uint32_t value_at(int x, int y) const { return (raw_at(x, y) + 128) >> 8; }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(config_.width) + static_cast<std::size_t>(x);
  }
  template <typename Pixel>
  void reset_from(ImageView<const Pixel> frame);
  template <typename Pixel>
  BackgroundResult apply_to(ImageView<const Pixel> frame, MutableImageView8 foreground);

  BackgroundConfig config_;
  std::vector<std::uint32_t> cells_;
};

}  // namespace irloc
