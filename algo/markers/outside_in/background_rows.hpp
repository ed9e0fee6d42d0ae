#pragma once
// The adaptive background's per-pixel rules (adaptive_background.hpp) as vector row kernels, each
// one read and write of its rows. Internal to AdaptiveBackground; every row has n pixels, any n.
//
// Fixed point: background cells Q8.8 (uint16 raw = grey * 256), frame pixels raw grey (Q8.0,
// compared as pixel << 8), the gain and the shadow ratio Q8 (raw = value * 256). The rescale's
// lanes are 32-bit, classify's and update's 16-bit: every intermediate is bounded below 2^16
// (noted at each step); the motion test compares grey levels in byte lanes.

#include <cstdint>

namespace irloc::outside_in::background_rows {

// cells[i] = min((cells[i] * gain_q8 + 128) >> 8, 0xFFFF), gain_q8 < 2^16: the global light change.
void rescale(std::uint16_t* cells, int n, std::uint32_t gain_q8);

struct ClassifyParams {
  std::uint16_t threshold_q8_8 = 0;  // |pixel - cell| above this is foreground (grey levels << 8)
  std::uint16_t shadow_ratio_q8 = 0;  // <= 256: pixel / cell in [ratio, 1) is a shadow
  std::uint8_t still_levels = 0;      // |pixel - previous| above this is motion
};

// foreground[i] = 255 where |frame - cell| > threshold and the pixel is not a shadow, else 0;
// motion[i] = 255 where |frame - previous| > still_levels, else 0; then previous[i] = frame[i].
// Returns the foreground count.
std::uint32_t classify(const std::uint8_t* frame, const std::uint16_t* cells, std::uint8_t* previous, int n,
                       const ClassifyParams& params, std::uint8_t* foreground, std::uint8_t* motion);

struct UpdateParams {
  int update_shift = 5;                // a followed cell moves by ceil(|frame - cell| / 2^shift)
  std::uint8_t absorb_frames = 10;     // >= 1: still foreground frames before it is background
};

// The gated update of one row (masks 0/255): where not foreground and not gated (grown and
// (motion or protected)) the cell follows the frame and still_count is 0; where foreground, not
// near motion (motion_grown) and not protected, still_count counts up and at absorb_frames the
// cell becomes the frame and still_count 0; elsewhere the cell stays and still_count is 0.
void update(const std::uint8_t* frame, const std::uint8_t* foreground, const std::uint8_t* motion,
            const std::uint8_t* grown, const std::uint8_t* motion_grown, const std::uint8_t* protect, int n,
            const UpdateParams& params, std::uint16_t* cells, std::uint8_t* still_count);

// update() of a row with no foreground within the gate radius (grown all 0): every cell follows
// the frame and still_count is 0.
void follow(const std::uint8_t* frame, int n, int update_shift, std::uint16_t* cells, std::uint8_t* still_count);

}  // namespace irloc::outside_in::background_rows
