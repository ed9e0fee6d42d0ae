#pragma once
// The median of a benchmark's per-iteration times (the upper middle of an even count); 0 if none.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace irloc::test {

inline double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace irloc::test
