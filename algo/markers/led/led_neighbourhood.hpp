#pragma once
// The mapped LEDs near the camera, so that per-frame work is bounded by the config and not by the
// map's size (docs/led_landmarks.md, "Cost"). Built at start-up: the LEDs sorted into square cells
// `range` metres wide in W's x-y (O(n log n) time, O(n) memory). near() visits the LEDs of the 3 x 3
// cells around a point: every LED within `range` of it, and some farther ones, which the caller's
// own range test drops, listed in the map's order (the order in which they claim detections). The most any point's 3 x 3 cells hold is computed at start-up; a map above
// `max_count` there is refused (std::invalid_argument), so near() lists at most max_count LEDs.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "algo/map/marker_map.hpp"

namespace irloc::led {

class LedNeighbourhood {
 public:
  LedNeighbourhood(const std::vector<LedLandmark>& leds, double range, std::size_t max_count);

  // The LEDs (indices in the map's led_landmarks, ascending) of the cells around `point`. Allocates
  // nothing once `leds` has room for densest().
  void near(const Eigen::Vector3d& point, std::vector<int>& leds) const;
  // The most LEDs near() lists for any point.
  std::size_t densest() const { return densest_; }

 private:
  struct Cell {
    std::int64_t x = 0, y = 0;
    std::uint32_t begin = 0, end = 0;  // its LEDs: order_[begin, end)
  };
  std::int64_t cell_of(double coordinate) const;
  const Cell* find(std::int64_t x, std::int64_t y) const;
  std::size_t count_around(std::int64_t x, std::int64_t y) const;

  double range_;
  std::vector<int> order_;   // LED indices sorted by cell
  std::vector<Cell> cells_;  // occupied cells, sorted by (x, y)
  std::size_t densest_ = 0;
};

}  // namespace irloc::led
