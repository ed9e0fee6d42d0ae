// The dot residuals before and after a calibration, side by side.

#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "host_sim/plots/canvas.hpp"

namespace irloc::sim {

using namespace drawing;

void plot_calibration_residuals(const std::filesystem::path& png, const std::vector<DotResidualRow>& residuals,
                                int image_width, int image_height) {
  constexpr int kCellPx = 20;  // image pixels per grid cell
  const int columns = (image_width + kCellPx - 1) / kCellPx, rows = (image_height + kCellPx - 1) / kCellPx;
  struct Cell {
    Eigen::Vector2d before = Eigen::Vector2d::Zero(), after = Eigen::Vector2d::Zero();
    int count = 0;
  };
  std::vector<Cell> cells(static_cast<std::size_t>(columns * rows));
  double rms_before = 0, rms_after = 0;
  for (const DotResidualRow& r : residuals) {
    const int column = std::clamp(static_cast<int>(r.pixel.x() + 0.5) / kCellPx, 0, columns - 1);
    const int row = std::clamp(static_cast<int>(r.pixel.y() + 0.5) / kCellPx, 0, rows - 1);
    Cell& cell = cells[static_cast<std::size_t>(row * columns + column)];
    cell.before += r.before;
    cell.after += r.after;
    ++cell.count;
    rms_before += r.before.squaredNorm();
    rms_after += r.after.squaredNorm();
  }
  const double n = std::max<double>(1, static_cast<double>(residuals.size()));
  rms_before = std::sqrt(rms_before / n);
  rms_after = std::sqrt(rms_after / n);
  double longest = 1e-9;
  for (const Cell& cell : cells) {
    if (cell.count > 0) longest = std::max(longest, cell.before.norm() / cell.count);
  }
  const double scale = 0.9 * kCellPx / longest;  // image pixels of arrow per pixel of residual

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
                  panel == 0 ? rms_before : rms_after);
    set_colour(cr, {0, 0, 0});
    text(cr, left, top - 8, label);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, left, top, panel_width, panel_height);
    cairo_stroke(cr);
    set_colour(cr, panel == 0 ? kEstimate : kTruth);
    cairo_set_line_width(cr, 1.5);
    for (int row = 0; row < rows; ++row) {
      for (int column = 0; column < columns; ++column) {
        const Cell& cell = cells[static_cast<std::size_t>(row * columns + column)];
        if (cell.count == 0) continue;
        const Eigen::Vector2d mean = (panel == 0 ? cell.before : cell.after) / cell.count;
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
  set_colour(cr, kGrey);
  char legend[160];
  std::snprintf(legend, sizeof legend, "an arrow of one cell (%d px) is a mean residual of %.2f px; dot: the cell's centre",
                kCellPx, kCellPx / scale);
  text(cr, margin, top + panel_height + 28, legend);
  canvas.save(png);
}

}  // namespace irloc::sim
