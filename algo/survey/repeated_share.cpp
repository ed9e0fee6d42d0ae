#include "algo/survey/repeated_share.hpp"

#include <algorithm>

namespace irloc::survey {

void RepeatedShare::add(int node, const MarkerSighting& sighting, std::uint64_t frame) {
  LastSighting& last = last_[static_cast<std::size_t>(node)];
  if (last.frame + 1 == frame) {
    const unsigned both = static_cast<unsigned>(last.cells & sighting.cells);
    for (int cell = 0; cell < dot::kCellCount; ++cell) {
      if ((both >> cell & 1u) == 0) continue;
      const auto now = sighting.residuals.col(cell);
      const auto before = last.residuals.col(cell);
      products_ += now.dot(before);
      squares_ += 0.5 * (now.squaredNorm() + before.squaredNorm());
    }
  }
  last.residuals = sighting.residuals;
  last.cells = sighting.cells;
  last.frame = frame;
}

double RepeatedShare::share() const { return squares_ > 0 ? std::clamp(products_ / squares_, 0.0, 1.0) : 0.0; }

}  // namespace irloc::survey
