#pragma once
// A frame's dot observations grouped by marker ID, for the survey's per-marker fits.

#include <cstddef>
#include <cstdint>
#include <span>

#include "algo/core/static_vector.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::survey {

// One marker's dots in a frame; repeated: a cell seen twice (two markers with one ID) or out of range.
struct MarkerDots {
  int id = -1;
  std::uint32_t cells = 0;
  bool repeated = false;
  StaticVector<PointObservation, dot::kCellCount> dots;
};

// The observations grouped by marker ID into groups, in the order first seen; their count. The
// observations of markers beyond the groups' room are counted in dropped.
std::size_t group_by_marker(const PointObservationList& observations, std::span<MarkerDots> groups,
                            std::uint64_t& dropped);

}  // namespace irloc::survey
