#pragma once
// Foreground that the cleaning (open_and_close.hpp) dropped just beyond a blob's extent: there the
// blob is short of the robot. A dark floor line (a tile joint) under a dark robot is within the
// background's shadow range (0.5-1.0 of the floor), so a one-pixel row of the robot drops out of
// the foreground; the robot's tip beyond it, a few rows thin, is then all removed by the opening.
// The box fit cannot tell such a blob from the whole box turned and moved: the fit explains it to
// a fraction of a pixel, 10 degrees and 40 mm off (docs/outside_in.md, step 4).
#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"

namespace irloc::outside_in {

// How far beyond the blob's bounding box a part of the foreground was dropped: the box fit's
// extent residuals (weight 1/2) stay within the mask's own 1 px for up to this much.
constexpr int kAllowedDroppedPx = 2;
// How far to look, px.
constexpr int kDroppedBand = 5;
// A part of the robot is at least as thick as the opening's 3 x 3 square along the blob's side;
// speckle beside it (a contact shadow's fringe, a face near the shadow range) is thinner.
constexpr int kSolidRun = 3;

// The largest k <= kDroppedBand such that the line k px beyond a side of the blob's bounding box
// (spanning that side and kDroppedBand more at each end) holds kSolidRun pixels in a row that are
// foreground but not in the cleaned mask; 0 when none does. At most 4 kDroppedBand lines.
int dropped_extent_px(const Blob& blob, ImageView8 foreground, ImageView8 mask);

}  // namespace irloc::outside_in
