#include "algo/markers/dot/dot_confidence.hpp"

#include <algorithm>
#include <cmath>

namespace irloc::dot {

double pose_confidence(const DotSourceConfig& config, std::span<const MarkerEvidence> markers, double rms_px) {
  double all_doubtful = 1.0;
  for (const MarkerEvidence& marker : markers) {
    const double margin = std::clamp(marker.margin / config.full_margin, 0.0, 1.0);
    all_doubtful *= 1.0 - std::clamp(marker.grey, 0.0, 1.0) * margin;
  }
  const double scaled_rms = rms_px / config.rms_scale_px;
  const double geometry = std::exp(-0.5 * scaled_rms * scaled_rms);
  return std::clamp((1.0 - all_doubtful) * geometry, 0.0, 1.0);
}

}  // namespace irloc::dot
