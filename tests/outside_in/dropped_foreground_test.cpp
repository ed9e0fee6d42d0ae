// Foreground the cleaning drops beyond a blob's extent (algo/markers/outside_in/dropped_foreground.hpp),
// on hand-drawn masks: a box's silhouette whole, and with one row across it dropped near its lowest
// tip, as a dark tile joint under a dark robot drops it (bench_outside_goal --seed=5, drive class,
// scene 1, frames 84-85).
#include "algo/markers/outside_in/dropped_foreground.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "algo/kernels/blob_labeller.hpp"
#include "algo/markers/outside_in/open_and_close.hpp"

namespace irloc::outside_in {
namespace {

constexpr int kWidth = 160, kHeight = 120;

// A silhouette like a box's seen obliquely: a hexagon, the footprint's rectangle (w x h px,
// turned by angle) joined to itself raised by `rise` px.
std::vector<std::uint8_t> draw_box(double angle, double cx, double cy) {
  constexpr double w = 56, h = 36, rise = 22, kFlatten = 0.6;
  const double c = std::cos(angle), s = std::sin(angle);
  std::array<Eigen::Vector2d, 8> corners;
  int n = 0;
  for (double lift : {0.0, rise})
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2)
        corners[n++] = {cx + c * sx * w / 2 - s * sy * h / 2, cy + kFlatten * (s * sx * w / 2 + c * sy * h / 2) - lift};
  std::vector<std::uint8_t> mask(kWidth * kHeight, 0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      // Inside the convex hull of the corners: no corner pair's line separates the pixel from all.
      const Eigen::Vector2d p(x, y);
      bool inside = true;
      for (int i = 0; i < 8 && inside; ++i)
        for (int j = 0; j < 8 && inside; ++j) {
          if (i == j) continue;
          const Eigen::Vector2d edge = corners[j] - corners[i];
          double least = 0, most = 0;
          for (const Eigen::Vector2d& k : corners) {
            const double side = edge.x() * (k.y() - corners[i].y()) - edge.y() * (k.x() - corners[i].x());
            least = std::min(least, side), most = std::max(most, side);
          }
          const double side = edge.x() * (p.y() - corners[i].y()) - edge.y() * (p.x() - corners[i].x());
          if (least >= -1e-9 && side < -1e-9) inside = false;  // all corners on one side, the pixel not
          if (most <= 1e-9 && side > 1e-9) inside = false;
        }
      mask[static_cast<std::size_t>(y * kWidth + x)] = inside ? 255 : 0;
    }
  return mask;
}

// How far beyond the cleaned mask's largest blob foreground was dropped; its lowest row.
int dropped_beyond_the_box(const std::vector<std::uint8_t>& foreground, int* lowest = nullptr) {
  std::vector<std::uint8_t> scratch(foreground.size()), mask(foreground.size());
  OpenAndClose open_and_close(kWidth);
  open_and_close.apply({foreground.data(), kWidth, kHeight}, {scratch.data(), kWidth, kHeight}, {mask.data(), kWidth, kHeight});
  BlobLabeller labeller(kWidth * kHeight / 8);
  BlobList blobs;
  labeller.label({mask.data(), kWidth, kHeight}, BlobParams{20}, blobs);
  const Blob* largest = nullptr;
  for (const Blob& blob : blobs)
    if (!largest || blob.area > largest->area) largest = &blob;
  if (!largest) return -1;
  if (lowest) *lowest = largest->y_max;
  return dropped_extent_px(*largest, {foreground.data(), kWidth, kHeight}, {mask.data(), kWidth, kHeight});
}

int lowest_row(const std::vector<std::uint8_t>& mask) {
  for (int y = kHeight - 1; y >= 0; --y)
    for (int x = 0; x < kWidth; ++x)
      if (mask[static_cast<std::size_t>(y * kWidth + x)]) return y;
  return -1;
}

// Whole, the silhouette loses only its tips to the opening, thinner than a solid run: nothing
// is dropped beyond it at any heading. With a row dropped 1-5 rows above its lowest tip (a tile
// joint in the shadow range), the opening drops the tip beyond it when the tip is 3 rows thin or
// less, and the closing bridges the gap when it is thicker: from 2 rows on, the count is how far
// the blob fell short, at every heading.
TEST(DroppedForeground, MeasuresHowFarATipCutOffByADroppedRowWasLost) {
  int beyond_the_fit = 0;
  for (int degrees = 0; degrees < 180; degrees += 5) {
    const double angle = degrees * std::numbers::pi / 180;
    const std::vector<std::uint8_t> whole = draw_box(angle, 80.3, 62.6);
    int whole_lowest = 0;
    EXPECT_EQ(dropped_beyond_the_box(whole, &whole_lowest), 0) << degrees << " deg";
    for (int above = 1; above <= 5; ++above) {
      std::vector<std::uint8_t> cut = whole;
      const int row = lowest_row(whole) - above;
      for (int x = 0; x < kWidth; ++x) cut[static_cast<std::size_t>(row * kWidth + x)] = 0;
      int lowest = 0;
      const int dropped = dropped_beyond_the_box(cut, &lowest);
      // A one-row tip may be thinner than a solid run; from 2 rows on it is counted exactly.
      const int lost = whole_lowest - lowest;
      EXPECT_EQ(dropped, lost >= 2 ? lost : dropped) << degrees << " deg, " << above << " rows above the tip";
      EXPECT_LE(dropped, lost) << degrees << " deg, " << above << " rows above the tip";
      beyond_the_fit += dropped > kAllowedDroppedPx;
    }
  }
  EXPECT_EQ(beyond_the_fit, 36);  // one cut at each heading shortens the blob by 3 rows
}

}  // namespace
}  // namespace irloc::outside_in
