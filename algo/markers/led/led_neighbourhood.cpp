#include "algo/markers/led/led_neighbourhood.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>

namespace irloc::led {

LedNeighbourhood::LedNeighbourhood(const std::vector<LedLandmark>& leds, double range, std::size_t max_count)
    : range_(range), order_(leds.size()) {
  std::iota(order_.begin(), order_.end(), 0);
  const auto key = [&](int led) {
    const Eigen::Vector3d& p = leds[static_cast<std::size_t>(led)].position;
    return std::pair(cell_of(p.x()), cell_of(p.y()));
  };
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) { return key(a) < key(b); });
  for (std::size_t k = 0; k < order_.size(); ++k) {
    const auto [x, y] = key(order_[k]);
    if (cells_.empty() || cells_.back().x != x || cells_.back().y != y) {
      cells_.push_back({x, y, static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(k)});
    }
    ++cells_.back().end;
  }
  // The points with the most LEDs around them lie in an occupied cell or next to one.
  for (const Cell& cell : cells_) {
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) densest_ = std::max(densest_, count_around(cell.x + dx, cell.y + dy));
    }
  }
  if (densest_ > max_count) {
    char message[200];
    std::snprintf(message, sizeof message,
                  "led path: %zu LED landmarks lie in one %g m square (3 x led.max_range), more than "
                  "led.max_leds_in_range (%zu)",
                  densest_, 3 * range, max_count);
    throw std::invalid_argument(message);
  }
}

void LedNeighbourhood::near(const Eigen::Vector3d& point, std::vector<int>& leds) const {
  leds.clear();
  const std::int64_t x = cell_of(point.x()), y = cell_of(point.y());
  for (std::int64_t dx = -1; dx <= 1; ++dx) {
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      if (const Cell* cell = find(x + dx, y + dy)) leds.insert(leds.end(), order_.begin() + cell->begin, order_.begin() + cell->end);
    }
  }
  std::sort(leds.begin(), leds.end());
}

std::int64_t LedNeighbourhood::cell_of(double coordinate) const {
  return static_cast<std::int64_t>(std::floor(coordinate / range_));
}

const LedNeighbourhood::Cell* LedNeighbourhood::find(std::int64_t x, std::int64_t y) const {
  const auto found = std::lower_bound(cells_.begin(), cells_.end(), std::pair(x, y), [](const Cell& cell, const auto& key) {
    return std::pair(cell.x, cell.y) < key;
  });
  return found != cells_.end() && found->x == x && found->y == y ? &*found : nullptr;
}

std::size_t LedNeighbourhood::count_around(std::int64_t x, std::int64_t y) const {
  std::size_t count = 0;
  for (std::int64_t dx = -1; dx <= 1; ++dx) {
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      if (const Cell* cell = find(x + dx, y + dy)) count += cell->end - cell->begin;
    }
  }
  return count;
}

}  // namespace irloc::led
