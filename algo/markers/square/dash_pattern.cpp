#include "algo/markers/square/dash_pattern.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace irloc {
namespace {

constexpr std::size_t kMaxBins = 1024;

}  // namespace

DashPattern measure_dash_pattern(std::span<const Eigen::Vector2d> points, const Eigen::Vector2d& start,
                                 const Eigen::Vector2d& end, const DashGeometry& geometry) {
  DashPattern pattern;
  const double length = (end - start).norm();
  const double first = geometry.tape_width;  // leave out the corner patches
  const double last = length - geometry.tape_width;
  if (last <= first) return pattern;
  // A quarter of the shorter of dash and gap, so that both span several bins.
  double bin = std::min(geometry.dash, geometry.gap) / 4.0;
  bin = std::max(bin, (last - first) / static_cast<double>(kMaxBins));
  const auto bins = std::min(kMaxBins, static_cast<std::size_t>((last - first) / bin));
  if (bins < 4) return pattern;

  std::array<std::uint8_t, kMaxBins> occupied{};
  std::array<std::uint16_t, kMaxBins> counts{};
  const Eigen::Vector2d along = (end - start) / length;
  const Eigen::Vector2d across(-along.y(), along.x());
  for (const Eigen::Vector2d& point : points) {
    const Eigen::Vector2d d = point - start;
    if (std::abs(d.dot(across)) > geometry.tape_width) continue;
    const double s = d.dot(along) - first;
    if (s < 0 || s >= static_cast<double>(bins) * bin) continue;
    const auto index = static_cast<std::size_t>(s / bin);
    occupied[index] = 1;
    counts[index] = static_cast<std::uint16_t>(std::min<int>(counts[index] + 1, 65535));
  }
  // A single empty bin between two full ones is a sampling hole (far tape is seen by few
  // pixels), not a gap: gaps span about four bins.
  for (std::size_t i = 1; i + 1 < bins; ++i) {
    if (occupied[i] == 0 && occupied[i - 1] == 1 && occupied[i + 1] == 1) occupied[i] = 2;
  }
  // Empty runs longer than a gap (plus blur) are hidden, not part of the pattern; shorter ones
  // between two covered bins are gaps.
  const auto longest_gap = static_cast<std::size_t>(std::ceil(geometry.gap / bin)) + 2;
  std::size_t visible = 0, filled = 0, run = 0, gaps = 0;
  bool covered_before = false;
  for (std::size_t i = 0; i <= bins; ++i) {
    if (i < bins && occupied[i] == 0) {
      ++run;
      continue;
    }
    if (run <= longest_gap) visible += run;
    if (run > 0 && run <= longest_gap && covered_before && i < bins) ++gaps;
    run = 0;
    if (i < bins) {
      ++visible;
      ++filled;
      covered_before = true;
    }
  }
  pattern.visible_fraction = static_cast<double>(visible) / static_cast<double>(bins);
  pattern.fill = visible > 0 ? static_cast<double>(filled) / static_cast<double>(visible) : 0.0;
  const double period = geometry.dash + geometry.gap;
  const double periods = static_cast<double>(visible) * bin / period;
  pattern.gap_rate = periods > 0 ? static_cast<double>(gaps) / periods : 0.0;
  // The phase, over the covered bins (their centres, weighed by their points: a bin a dash only
  // touches counts little), from either end.
  double from_start = 0, from_end = 0, weight = 0;
  const double turn_per_metre = 2 * std::numbers::pi / period;
  for (std::size_t i = 0; i < bins; ++i) {
    if (counts[i] == 0) continue;
    const double s = first + (static_cast<double>(i) + 0.5) * bin;
    const double n = counts[i];
    weight += n;
    from_start += n * std::cos(turn_per_metre * (s - geometry.dash / 2));
    from_end += n * std::cos(turn_per_metre * (length - s - geometry.dash / 2));
  }
  if (weight > 0) {
    pattern.phase_from_start = from_start / weight;
    pattern.phase_from_end = from_end / weight;
  }
  return pattern;
}

}  // namespace irloc
