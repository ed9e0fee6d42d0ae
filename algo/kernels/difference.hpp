#pragma once
// Strobe-pair difference: the LED-on frame minus the LED-off frame, saturating at 0, so that only
// what the robot's own IR lights up (retro-reflective markers) stays bright.

#include "algo/core/image_view.hpp"

namespace irloc {

// out(x, y) = max(on(x, y) - off(x, y), 0) in the input depth (cv::subtract on CV_8U/CV_16U).
// on, off and out have the same size; any strides; out may alias on or off exactly.
void subtract_saturating(ImageView8 on, ImageView8 off, MutableImageView8 out);
void subtract_saturating(ImageView16 on, ImageView16 off, MutableImageView16 out);

}  // namespace irloc
