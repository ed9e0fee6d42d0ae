#include "algo/markers/outside_in/dropped_foreground.hpp"

namespace irloc::outside_in {
namespace {

// Whether the line from (x, y) in steps of (dx, dy), `length` pixels, holds kSolidRun dropped
// pixels (foreground, not in the mask) in a row; the parts outside the image are not.
bool holds_solid_run(ImageView8 foreground, ImageView8 mask, int x, int y, int dx, int dy, int length) {
  int run = 0;
  for (int k = 0; k < length; ++k, x += dx, y += dy) {
    const bool inside = x >= 0 && y >= 0 && x < foreground.width() && y < foreground.height();
    run = inside && foreground.at(x, y) != 0 && mask.at(x, y) == 0 ? run + 1 : 0;
    if (run >= kSolidRun) return true;
  }
  return false;
}

}  // namespace

int dropped_extent_px(const Blob& blob, ImageView8 foreground, ImageView8 mask) {
  const int b = kDroppedBand;
  const int wide = blob.width() + 2 * b, tall = blob.height() + 2 * b;
  const auto line_holds = [&](int k) {
    return holds_solid_run(foreground, mask, blob.x_min - k, blob.y_min - b, 0, 1, tall) ||
           holds_solid_run(foreground, mask, blob.x_max + k, blob.y_min - b, 0, 1, tall) ||
           holds_solid_run(foreground, mask, blob.x_min - b, blob.y_min - k, 1, 0, wide) ||
           holds_solid_run(foreground, mask, blob.x_min - b, blob.y_max + k, 1, 0, wide);
  };
  int depth = line_holds(1) ? 1 : 0;
  for (int k = 2; k <= b && line_holds(k); ++k) depth = k;
  return depth;
}

}  // namespace irloc::outside_in
