#pragma once
// Verifies a strobe pair from the pictures themselves before a pose is computed from it: the
// frame recorded as LED-on must be the brighter one where they differ (retro-reflectors and the
// lit ceiling), never the other way round. The evidence, StrobeCounts, is counted by the fused
// front end in its one pass over the pair (fused_front_end.hpp); the Localizer gives the verdict.

#include <cstdint>

namespace irloc {

enum class StrobeVerdict {
  verified,     // the on-frame is brighter where the two differ
  swapped,      // the off-frame is brighter: the LED state assignment is wrong (sync lost)
  no_contrast,  // too little difference to tell (LEDs dead, lens covered, nothing in view)
};

struct StrobeCheckSettings {
  int noise_level = 12;           // a pixel differs when |on - off| exceeds this (image units), >= 0
  double min_contrast_ratio = 3;  // brighter-in-on pixels must outnumber brighter-in-off ones this much
  int min_pixels = 4;             // and be at least this many
};

// Pixels of a pair that differ by more than the noise level, each way.
struct StrobeCounts {
  std::uint64_t brighter_on = 0;   // on - off > noise_level
  std::uint64_t brighter_off = 0;  // off - on > noise_level
};

StrobeVerdict strobe_verdict(const StrobeCounts& counts, const StrobeCheckSettings& settings);

}  // namespace irloc
