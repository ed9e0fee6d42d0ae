#include "algo/survey/marker_dots.hpp"

namespace irloc::survey {

// The observations grouped by marker ID into groups, in the order first seen; their count. The
// observations of markers beyond the groups' room are counted in dropped.
std::size_t group_by_marker(const PointObservationList& observations, std::span<MarkerDots> groups,
                            std::uint64_t& dropped) {
  std::size_t group_count = 0;
  for (const PointObservation& observation : observations) {
    std::size_t g = 0;
    while (g < group_count && groups[g].id != observation.landmark) ++g;
    if (g == group_count) {
      if (group_count == groups.size()) {
        ++dropped;
        continue;
      }
      groups[group_count++].id = observation.landmark;
    }
    MarkerDots& group = groups[g];
    const std::uint32_t bit = 1u << (observation.point & 31);
    if (observation.point < 0 || observation.point >= dot::kCellCount || (group.cells & bit) != 0 ||
        !group.dots.push_back(observation)) {
      group.repeated = true;
      continue;
    }
    group.cells |= bit;
  }
  return group_count;
}

}  // namespace irloc::survey
