#include "algo/markers/dot/cell_contrast.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

#include "algo/geometry/homography.hpp"

namespace irloc::dot {
namespace {

// Mean of max(on - off, 0) over the square of half-size radius around pixel; -1 when the square
// leaves the image.
template <typename Pixel>
double mean_difference(ImageView<const Pixel> on, ImageView<const Pixel> off, const Eigen::Vector2d& pixel,
                       int radius) {
  const int cx = static_cast<int>(std::lround(pixel.x()));
  const int cy = static_cast<int>(std::lround(pixel.y()));
  if (cx - radius < 0 || cy - radius < 0 || cx + radius >= on.width() || cy + radius >= on.height()) return -1;
  std::uint64_t sum = 0;
  for (int y = cy - radius; y <= cy + radius; ++y) {
    for (int x = cx - radius; x <= cx + radius; ++x) {
      const int a = on.at(x, y);
      const int b = off.at(x, y);
      sum += static_cast<std::uint64_t>(a > b ? a - b : 0);
    }
  }
  const int side = 2 * radius + 1;
  return static_cast<double>(sum) / (side * side);
}

}  // namespace

CellContrast measure_cell_contrast(const DecodedCells& decoded, const NominalPlane& plane, const CameraModel& camera,
                                   const GrayImageView& on, const GrayImageView& off, int window_radius) {
  CellContrast result;
  std::array<double, kCellCount> level{};
  for (int cell = 0; cell < kCellCount; ++cell) {
    const Eigen::Vector2d grid(cell_column(cell), cell_row(cell));
    Eigen::Vector2d pixel;
    if (!camera.project(plane.point(apply_homography(decoded.grid_to_plane, grid)), pixel)) return result;
    level[static_cast<std::size_t>(cell)] = std::visit(
        [&](const auto& on_view) {
          using View = std::decay_t<decltype(on_view)>;
          return mean_difference(on_view, std::get<View>(off), pixel, window_radius);
        },
        on);
    if (level[static_cast<std::size_t>(cell)] < 0) return result;  // a cell off the image: no verdict
  }
  result.reference_level = (level[kCellO] + level[kCellX] + level[kCellY]) / 3.0;
  if (result.reference_level <= 0) return result;
  double margin = 1.0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    const double ratio = level[static_cast<std::size_t>(cell)] / result.reference_level;
    const bool populated = (decoded.cells >> cell) & 1u;
    margin = std::min(margin, populated ? 2.0 * (ratio - 0.5) : 2.0 * (0.5 - ratio));
  }
  result.margin = std::clamp(margin, -1.0, 1.0);
  return result;
}

}  // namespace irloc::dot
