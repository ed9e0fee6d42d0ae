// The dot residuals before and after a calibration, side by side.

#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "host_sim/plots/canvas.hpp"

namespace irloc::sim {

using namespace drawing;

namespace {

constexpr int kCellPx = 20;  // image pixels per grid cell

// The residuals summed per grid cell of the image, before and after.
struct ResidualGrid {
  struct Cell {
    Eigen::Vector2d before = Eigen::Vector2d::Zero(), after = Eigen::Vector2d::Zero();
    int count = 0;
  };
  int columns, rows;
  std::vector<Cell> cells;
  double rms_before = 0, rms_after = 0;  // px, over every residual

  ResidualGrid(const std::vector<DotResidualRow>& residuals, int image_width, int image_height)
      : columns((image_width + kCellPx - 1) / kCellPx), rows((image_height + kCellPx - 1) / kCellPx),
        cells(static_cast<std::size_t>(columns * rows)) {
    for (const DotResidualRow& r : residuals) {
      const int column = std::clamp(static_cast<int>(r.pixel.x() + 0.5) / kCellPx, 0, columns - 1);
      const int row = std::clamp(static_cast<int>(r.pixel.y() + 0.5) / kCellPx, 0, rows - 1);
      Cell& cell = at(row, column);
      cell.before += r.before;
      cell.after += r.after;
      ++cell.count;
      rms_before += r.before.squaredNorm();
      rms_after += r.after.squaredNorm();
    }
    const double n = std::max<double>(1, static_cast<double>(residuals.size()));
    rms_before = std::sqrt(rms_before / n);
    rms_after = std::sqrt(rms_after / n);
  }
  Cell& at(int row, int column) { return cells[static_cast<std::size_t>(row * columns + column)]; }
  const Cell& at(int row, int column) const { return cells[static_cast<std::size_t>(row * columns + column)]; }
  // The arrows' scale (image pixels of arrow per pixel of residual): the longest mean residual
  // before is 0.9 of a cell.
  double arrow_scale() const {
    double longest = 1e-9;
    for (const Cell& cell : cells) {
      if (cell.count > 0) longest = std::max(longest, cell.before.norm() / cell.count);
    }
    return 0.9 * kCellPx / longest;
  }
};

// One panel: each cell's mean residual as an arrow from the cell's centre; `zoom` canvas pixels
// per image pixel.
void draw_residual_panel(cairo_t* cr, const ResidualGrid& grid, bool after, double left, double top, double zoom,
                         double scale) {
  for (int row = 0; row < grid.rows; ++row) {
    for (int column = 0; column < grid.columns; ++column) {
      const ResidualGrid::Cell& cell = grid.at(row, column);
      if (cell.count == 0) continue;
      const Eigen::Vector2d mean = (after ? cell.after : cell.before) / cell.count;
      const double x = left + (column + 0.5) * kCellPx * zoom, y = top + (row + 0.5) * kCellPx * zoom;
      const double dx = mean.x() * scale * zoom, dy = mean.y() * scale * zoom;
      cairo_arc(cr, x, y, 1.2, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
      cairo_move_to(cr, x, y);
      cairo_line_to(cr, x + dx, y + dy);
      cairo_stroke(cr);
    }
  }
}

}  // namespace

void plot_calibration_residuals(const std::filesystem::path& png, const std::vector<DotResidualRow>& residuals,
                                int image_width, int image_height) {
  const ResidualGrid grid(residuals, image_width, image_height);
  const double scale = grid.arrow_scale();
  const double zoom = 640.0 / image_width;  // each panel 640 canvas pixels wide
  const double panel_width = image_width * zoom, panel_height = image_height * zoom;
  const double margin = 30, top = 60;
  Canvas canvas(static_cast<int>(2 * panel_width + 3 * margin), static_cast<int>(panel_height + top + 45));
  cairo_t* cr = canvas.cr();
  set_colour(cr, {0, 0, 0});
  char title[200];
  std::snprintf(title, sizeof title, "Dot reprojection residuals over the image (%zu dots; mean per %d px cell, arrows x%.0f)",
                residuals.size(), kCellPx, scale);
  text(cr, margin, 24, title);
  for (int panel = 0; panel < 2; ++panel) {
    const double left = margin + panel * (panel_width + margin);
    char label[96];
    std::snprintf(label, sizeof label, "%s: RMS %.3f px", panel == 0 ? "before (input calibration)" : "after --calibrate",
                  panel == 0 ? grid.rms_before : grid.rms_after);
    set_colour(cr, {0, 0, 0});
    text(cr, left, top - 8, label);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, left, top, panel_width, panel_height);
    cairo_stroke(cr);
    set_colour(cr, panel == 0 ? kEstimate : kTruth);
    cairo_set_line_width(cr, 1.5);
    draw_residual_panel(cr, grid, panel == 1, left, top, zoom, scale);
  }
  set_colour(cr, kGrey);
  char legend[160];
  std::snprintf(legend, sizeof legend, "an arrow of one cell (%d px) is a mean residual of %.2f px; dot: the cell's centre",
                kCellPx, kCellPx / scale);
  text(cr, margin, top + panel_height + 28, legend);
  canvas.save(png);
}

}  // namespace irloc::sim
