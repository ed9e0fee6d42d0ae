#pragma once
// The foreground threshold of the strobe difference from its own noise, so that one config serves
// 8-, 10- and 12-bit sensors and dim or bright ceilings. On a sparse IR difference nearly every
// pixel is background: its median m and upper quartile q75 of max(on - off, 0) give the noise
// sigma = (q75 - m) / 0.6745 (the upper half of a Gaussian, which stays valid when the LED-lit
// ceiling makes the background difference positive and when half of it saturates at 0).
// threshold = m + sigmas * sigma, at least min_threshold.

#include <array>
#include <cstdint>

#include "algo/core/image_view.hpp"

namespace irloc::dot {

class NoiseThreshold {
 public:
  // row_step: every row_step-th row is sampled.
  NoiseThreshold(double sigmas, std::uint32_t min_threshold, int row_step)
      : sigmas_(sigmas), min_threshold_(min_threshold), row_step_(row_step) {}

  // The threshold for one strobe pair, in grey levels of the frames. Allocates nothing.
  std::uint32_t estimate(ImageView8 on, ImageView8 off);
  std::uint32_t estimate(ImageView16 on, ImageView16 off);

  double last_sigma() const { return last_sigma_; }

 private:
  std::uint32_t from_histogram(int bins);

  double sigmas_;
  std::uint32_t min_threshold_;
  int row_step_;
  double last_sigma_ = 0;
  std::array<std::uint32_t, 1024> bins_{};  // one grey level per bin; larger differences in the last
};

}  // namespace irloc::dot
