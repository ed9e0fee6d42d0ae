#include "algo/markers/square/dash_pattern.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace irloc::square {
namespace {

constexpr std::size_t kMaxBins = 1024;

// The side's stretch between its corner patches in bins along it: which hold tape points (1; 2:
// a sampling hole filled), and how many.
struct SideBins {
  double first = 0;  // where bin 0 starts, metres from the side's start
  double bin = 0;    // metres
  std::size_t count = 0;
  std::array<std::uint8_t, kMaxBins> occupied{};
  std::array<std::uint16_t, kMaxBins> points{};
};

void bin_points(std::span<const Eigen::Vector2d> points, const Eigen::Vector2d& start, const Eigen::Vector2d& along,
                double tape_width, SideBins& bins) {
  const Eigen::Vector2d across(-along.y(), along.x());
  for (const Eigen::Vector2d& point : points) {
    const Eigen::Vector2d d = point - start;
    if (std::abs(d.dot(across)) > tape_width) continue;
    const double s = d.dot(along) - bins.first;
    if (s < 0 || s >= static_cast<double>(bins.count) * bins.bin) continue;
    const auto index = static_cast<std::size_t>(s / bins.bin);
    bins.occupied[index] = 1;
    bins.points[index] = static_cast<std::uint16_t>(std::min<int>(bins.points[index] + 1, 65535));
  }
  // A single empty bin between two full ones is a sampling hole (far tape is seen by few
  // pixels), not a gap: gaps span about four bins.
  for (std::size_t i = 1; i + 1 < bins.count; ++i) {
    if (bins.occupied[i] == 0 && bins.occupied[i - 1] == 1 && bins.occupied[i + 1] == 1) bins.occupied[i] = 2;
  }
}

// The visible fraction, the fill and the gap rate. Empty runs longer than a gap (plus blur) are
// hidden, not part of the pattern; shorter ones between two covered bins are gaps.
void measure_runs(const SideBins& bins, const DashGeometry& geometry, DashPattern& pattern) {
  const auto longest_gap = static_cast<std::size_t>(std::ceil(geometry.gap / bins.bin)) + 2;
  std::size_t visible = 0, filled = 0, run = 0, gaps = 0;
  bool covered_before = false;
  for (std::size_t i = 0; i <= bins.count; ++i) {
    if (i < bins.count && bins.occupied[i] == 0) {
      ++run;
      continue;
    }
    if (run <= longest_gap) visible += run;
    if (run > 0 && run <= longest_gap && covered_before && i < bins.count) ++gaps;
    run = 0;
    if (i < bins.count) {
      ++visible;
      ++filled;
      covered_before = true;
    }
  }
  pattern.visible_fraction = static_cast<double>(visible) / static_cast<double>(bins.count);
  pattern.fill = visible > 0 ? static_cast<double>(filled) / static_cast<double>(visible) : 0.0;
  const double periods = static_cast<double>(visible) * bins.bin / (geometry.dash + geometry.gap);
  pattern.gap_rate = periods > 0 ? static_cast<double>(gaps) / periods : 0.0;
}

// The phase, over the covered bins (their centres, weighed by their points: a bin a dash only
// touches counts little), from either end.
void measure_phase(const SideBins& bins, double length, const DashGeometry& geometry, DashPattern& pattern) {
  double from_start = 0, from_end = 0, weight = 0;
  const double turn_per_metre = 2 * std::numbers::pi / (geometry.dash + geometry.gap);
  for (std::size_t i = 0; i < bins.count; ++i) {
    if (bins.points[i] == 0) continue;
    const double s = bins.first + (static_cast<double>(i) + 0.5) * bins.bin;
    const double n = bins.points[i];
    weight += n;
    from_start += n * std::cos(turn_per_metre * (s - geometry.dash / 2));
    from_end += n * std::cos(turn_per_metre * (length - s - geometry.dash / 2));
  }
  if (weight > 0) {
    pattern.phase_from_start = from_start / weight;
    pattern.phase_from_end = from_end / weight;
  }
}

}  // namespace

DashPattern measure_dash_pattern(std::span<const Eigen::Vector2d> points, const Eigen::Vector2d& start,
                                 const Eigen::Vector2d& end, const DashGeometry& geometry) {
  DashPattern pattern;
  const double length = (end - start).norm();
  SideBins bins;
  bins.first = geometry.tape_width;  // leave out the corner patches
  const double last = length - geometry.tape_width;
  if (last <= bins.first) return pattern;
  // A quarter of the shorter of dash and gap, so that both span several bins.
  bins.bin = std::max(std::min(geometry.dash, geometry.gap) / 4.0, (last - bins.first) / static_cast<double>(kMaxBins));
  bins.count = std::min(kMaxBins, static_cast<std::size_t>((last - bins.first) / bins.bin));
  if (bins.count < 4) return pattern;
  bin_points(points, start, (end - start) / length, geometry.tape_width, bins);
  measure_runs(bins, geometry, pattern);
  measure_phase(bins, length, geometry, pattern);
  return pattern;
}

}  // namespace irloc::square
