#pragma once
// Verifies a strobe pair from the pictures themselves before a pose is computed from it: the
// frame recorded as LED-on must be the brighter one where they differ (retro-reflectors and the
// lit ceiling), never the other way round. A pair that fails gives no pose.

#include "algo/frames/frame.hpp"

namespace irloc::firmware {

enum class StrobeVerdict {
  verified,     // the on-frame is brighter where the two differ
  swapped,      // the off-frame is brighter: the LED state assignment is wrong (sync lost)
  no_contrast,  // too little difference to tell (LEDs dead, lens covered, nothing in view)
};

struct StrobeCheckSettings {
  int noise_level = 12;           // a pixel differs when |on - off| exceeds this (image units)
  double min_contrast_ratio = 3;  // brighter-in-on pixels must outnumber brighter-in-off ones this much
  int min_pixels = 4;             // and be at least this many
};

// Both frames must have the same size and pixel type (else no_contrast). Reads every pixel of
// both frames once; allocates nothing.
StrobeVerdict check_strobe_pair(const Frame& on, const Frame& off, const StrobeCheckSettings& settings);

}  // namespace irloc::firmware
