#include "algo/markers/dot/cell_contrast.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <variant>

#include "algo/geometry/homography.hpp"

namespace irloc::dot {
namespace {

// The populated cells read at least, for a reference level measured on more than one dot.
constexpr int kMinReferenceCells = 3;

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

// Mean of max(on - off, 0) around pixel (as mean_difference), for either pixel depth.
double cell_level(const GrayImageView& on, const GrayImageView& off, const Eigen::Vector2d& pixel, int radius) {
  return std::visit(
      [&](const auto& on_view) {
        using View = std::decay_t<decltype(on_view)>;
        return mean_difference(on_view, std::get<View>(off), pixel, radius);
      },
      on);
}

// The margin of the least clear cell among `read` (their levels known), against the mean level of
// the `reference` cells.
CellContrast contrast_of_levels(const std::array<double, kCellCount>& level, CellMask populated, CellMask read,
                                CellMask reference) {
  CellContrast result;
  int references = 0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    if ((reference >> cell) & 1u) {
      result.reference_level += level[static_cast<std::size_t>(cell)];
      ++references;
    }
  }
  if (references == 0) return result;
  result.reference_level /= references;
  if (result.reference_level <= 0) return result;
  double margin = 1.0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    if (!((read >> cell) & 1u)) continue;
    const double ratio = level[static_cast<std::size_t>(cell)] / result.reference_level;
    const bool is_populated = (populated >> cell) & 1u;
    margin = std::min(margin, is_populated ? 2.0 * (ratio - 0.5) : 2.0 * (0.5 - ratio));
  }
  result.margin = std::clamp(margin, -1.0, 1.0);
  return result;
}

}  // namespace

CellContrast measure_cell_contrast(const DecodedCells& decoded, const NominalPlane& plane, const CameraModel& camera,
                                   const GrayImageView& on, const GrayImageView& off, int window_radius) {
  std::array<double, kCellCount> level{};
  for (int cell = 0; cell < kCellCount; ++cell) {
    const Eigen::Vector2d grid(cell_column(cell), cell_row(cell));
    Eigen::Vector2d pixel;
    if (!camera.project(plane.point(apply_homography(decoded.grid_to_plane, grid)), pixel)) return {};
    level[static_cast<std::size_t>(cell)] = cell_level(on, off, pixel, window_radius);
    if (level[static_cast<std::size_t>(cell)] < 0) return {};  // a cell off the image: no verdict
  }
  constexpr CellMask kEveryCell = 0xffff;
  return contrast_of_levels(level, decoded.cells, kEveryCell, kDirectionCells);
}

CellContrast measure_cell_contrast_at(const std::array<Eigen::Vector2d, kCellCount>& pixels, CellMask populated,
                                      CellMask predicted, const GrayImageView& on, const GrayImageView& off,
                                      int window_radius) {
  std::array<double, kCellCount> level{};
  CellMask read = 0;
  for (int cell = 0; cell < kCellCount; ++cell) {
    if (!((predicted >> cell) & 1u)) continue;
    level[static_cast<std::size_t>(cell)] = cell_level(on, off, pixels[static_cast<std::size_t>(cell)], window_radius);
    if (level[static_cast<std::size_t>(cell)] >= 0) read = static_cast<CellMask>(read | (1u << cell));
  }
  const CellMask reference = read & populated;
  if (std::popcount(reference) < kMinReferenceCells) return {};
  return contrast_of_levels(level, populated, read, reference);
}

}  // namespace irloc::dot
