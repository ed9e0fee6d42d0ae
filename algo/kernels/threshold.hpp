#pragma once
// Fixed thresholding of a grey image into a 0 / max_value mask.

#include <cstdint>

#include "algo/core/image_view.hpp"

namespace irloc {

// out(x, y) = in(x, y) > threshold ? max_value : 0 (cv::THRESH_BINARY). The mask is 8-bit for
// either input depth. in and out have the same size; any strides; out may alias an 8-bit in.
void threshold_binary(ImageView8 in, std::uint8_t threshold, std::uint8_t max_value, MutableImageView8 out);
void threshold_binary(ImageView16 in, std::uint16_t threshold, std::uint8_t max_value, MutableImageView8 out);

}  // namespace irloc
