#pragma once
// Pairs each LED-on frame with an adjacent LED-off frame of the strobed stream.

#include <optional>

#include "algo/frames/frame.hpp"

namespace irloc {

// An LED-on frame and the LED-off frame its difference is taken against. off is empty when the
// on-frame has no usable partner (both neighbours dropped or not LED-off): the pose attempt for
// that frame is then reported as `none`, never computed against a wrong frame.
struct StrobePair {
  Frame on;
  std::optional<Frame> off;
};

// Frames go in in capture order. An on-frame pairs with the off-frame just before it (sequence
// number one less); failing that, with the off-frame just after it. A gap in the sequence
// numbers is a dropped frame and is never paired across, nor are two frames of the same LED
// state. Every on-frame comes out exactly once, so each gets one pose attempt.
//
// Lifetime: the pairer keeps copies of up to two earlier frames, so a frame source must keep
// each frame's pixels valid until two more frames have been pushed.
class StrobePairer {
 public:
  // At most one pair is complete after each frame.
  std::optional<StrobePair> push(const Frame& frame);
  // The on-frame still waiting for a partner, at the end of the stream.
  std::optional<StrobePair> flush();

 private:
  std::optional<Frame> previous_;    // the last frame pushed
  std::optional<Frame> waiting_on_;  // an on-frame that found no off-frame before it
};

}  // namespace irloc
