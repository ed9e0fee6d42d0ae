#include "algo/kernels/strobe_check.hpp"

namespace irloc {

StrobeVerdict strobe_verdict(const StrobeCounts& counts, const StrobeCheckSettings& settings) {
  const auto min_pixels = static_cast<std::uint64_t>(settings.min_pixels);
  const auto on_wins = static_cast<double>(counts.brighter_on);
  const auto off_wins = static_cast<double>(counts.brighter_off);
  if (counts.brighter_on >= min_pixels && on_wins >= settings.min_contrast_ratio * off_wins) return StrobeVerdict::verified;
  if (counts.brighter_off >= min_pixels && off_wins >= settings.min_contrast_ratio * on_wins) return StrobeVerdict::swapped;
  return StrobeVerdict::no_contrast;
}

}  // namespace irloc
