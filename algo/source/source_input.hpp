#pragma once
// What every pose source is handed for one pose attempt: the frame the pose is for and, in
// strobed mode, its LED-off partner. The Localizer checks both once before any source runs:
// same pixel depth, the calibrated size. A source never sees a frame it would have to refuse
// for its size.

#include "algo/frames/frame.hpp"

namespace irloc {

struct SourceInput {
  const Frame& on;    // the LED-on frame (in outside-in mode: the one frame)
  const Frame* off;   // its LED-off partner; nullptr when it has none
};

}  // namespace irloc
