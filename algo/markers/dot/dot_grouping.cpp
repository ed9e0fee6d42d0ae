#include "algo/markers/dot/dot_grouping.hpp"

#include <algorithm>
#include <array>

namespace irloc::dot {
namespace {

std::uint8_t find_root(std::array<std::uint8_t, kMaxDotCandidates>& parent, std::uint8_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

GroupingCounters group_candidates(const DotCandidateList& candidates, double link_distance, DotGroupList& groups) {
  static_assert(kMaxDotCandidates <= 256, "candidate indices are bytes");
  groups.clear();
  GroupingCounters counters;
  const std::size_t n = candidates.size();
  std::array<std::uint8_t, kMaxDotCandidates> parent{};
  for (std::size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint8_t>(i);

  const double link_squared = link_distance * link_distance;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if ((candidates[i].plane - candidates[j].plane).squaredNorm() > link_squared) continue;
      const std::uint8_t a = find_root(parent, static_cast<std::uint8_t>(i));
      const std::uint8_t b = find_root(parent, static_cast<std::uint8_t>(j));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the root stays the smallest index
    }
  }

  // Each root, in index order, opens a group; members follow in index order.
  std::array<std::int16_t, kMaxDotCandidates> group_of_root{};
  std::array<std::uint8_t, kMaxDotCandidates> size_of_root{};
  for (std::size_t i = 0; i < n; ++i) ++size_of_root[find_root(parent, static_cast<std::uint8_t>(i))];
  for (std::size_t i = 0; i < n; ++i) {
    group_of_root[i] = -1;
    if (parent[i] != i) continue;
    if (size_of_root[i] < 3) {
      ++counters.too_small;
    } else if (size_of_root[i] > kMaxGroupSize) {
      ++counters.too_large;
    } else if (groups.push_back(DotGroup{})) {
      group_of_root[i] = static_cast<std::int16_t>(groups.size() - 1);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::int16_t group = group_of_root[find_root(parent, static_cast<std::uint8_t>(i))];
    if (group >= 0) groups[static_cast<std::size_t>(group)].members.push_back(static_cast<std::uint8_t>(i));
  }
  counters.groups = static_cast<std::uint32_t>(groups.size());
  counters.dropped = groups.dropped();
  return counters;
}

}  // namespace irloc::dot
