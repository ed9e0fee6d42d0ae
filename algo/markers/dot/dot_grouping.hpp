#pragma once
// Stage 2: candidates grouped into marker hypotheses by metric proximity in the nominal ceiling
// plane. Two dots of one marker are at most 3 pitches from a neighbour in the same marker (the
// sparsest marker, code 0, is just O, X and Y), so dots closer than link_factor * 3 pitch are
// linked and each connected set is one group. This holds under perspective and lens distortion
// because distances are measured on the ceiling, not in pixels; markers must lie farther apart
// than that link distance (docs/dot_markers.md).

#include <cstddef>
#include <cstdint>

#include "algo/core/static_vector.hpp"
#include "algo/markers/dot/dot_candidates.hpp"

namespace irloc::dot {

// At most 13 dots make a marker; room for a few stray blobs besides.
inline constexpr std::size_t kMaxGroupSize = 20;
inline constexpr std::size_t kMaxGroups = 24;

struct DotGroup {
  StaticVector<std::uint8_t, kMaxGroupSize> members;  // indices into the candidate list
};
using DotGroupList = StaticVector<DotGroup, kMaxGroups>;

struct GroupingCounters {
  std::uint32_t groups = 0;        // groups of at least 3 dots
  std::uint32_t too_small = 0;     // fewer than 3 dots: cannot be a marker
  std::uint32_t too_large = 0;     // more than kMaxGroupSize dots: a clutter patch, not used
  std::uint32_t dropped = 0;       // did not fit in the group list (overflow)
};

// Clears groups and fills it. link_distance: metres in the nominal plane. Allocates nothing;
// work is O(n^2) in the (bounded) number of candidates.
GroupingCounters group_candidates(const DotCandidateList& candidates, double link_distance, DotGroupList& groups);

}  // namespace irloc::dot
