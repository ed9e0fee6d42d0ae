// A scalar field over the floor or ceiling (the planning tools).

#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "host_sim/plots/canvas.hpp"

namespace irloc::sim {

using namespace drawing;
constexpr double kPi = std::numbers::pi;

void plot_heat_map(const std::filesystem::path& png, const HeatMap& map) {
  const double plot = 480;
  const double scale = plot / std::max(map.x1 - map.x0, map.y1 - map.y0);
  const Axes axes{70, 40, (map.x1 - map.x0) * scale, (map.y1 - map.y0) * scale, map.x0, map.x1, map.y0, map.y1};
  Canvas canvas(static_cast<int>(axes.width) + 200, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  const double cell_w = axes.width / map.columns, cell_h = axes.height / map.rows;
  const double span = map.high > map.low ? map.high - map.low : 1;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.columns; ++c) {
      const double value = map.values[static_cast<std::size_t>(r * map.columns + c)];
      // NaN: a point the camera does not see.
      set_colour(cr, std::isnan(value) ? Colour{0.8, 0.8, 0.8} : colour_scale((value - map.low) / span));
      cairo_rectangle(cr, axes.left + c * cell_w, axes.top + axes.height - (r + 1) * cell_h, cell_w + 0.5, cell_h + 0.5);
      cairo_fill(cr);
    }
  }
  cairo_set_source_rgb(cr, 1, 1, 1);
  for (const Eigen::Vector2d& mark : map.marks) {
    cairo_arc(cr, axes.px(mark.x()), axes.py(mark.y()), 3, 0, 2 * kPi);
    cairo_fill(cr);
  }
  axes.draw(cr, "x (m)", "y (m)", map.title, false);

  // Colour bar.
  const double bar_x = axes.left + axes.width + 30, bar_top = axes.top, bar_height = axes.height;
  const int steps = map.discrete ? static_cast<int>(std::round(map.high - map.low)) + 1 : 100;
  for (int i = 0; i < steps; ++i) {
    const double t = steps > 1 ? static_cast<double>(i) / (steps - 1) : 0;
    set_colour(cr, colour_scale(t));
    cairo_rectangle(cr, bar_x, bar_top + bar_height * (1 - static_cast<double>(i + 1) / steps), 20, bar_height / steps + 0.5);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_font_size(cr, 11);
  const double step = map.discrete ? std::max(1.0, nice_step(span, 6)) : nice_step(span, 6);
  // nice_step gives about 6 ticks; the count bounds the loop whatever the scale.
  const double first_tick = std::ceil(map.low / step) * step;
  for (int tick = 0; tick <= 12; ++tick) {
    const double v = first_tick + tick * step;
    if (v > map.high + 1e-9 * span) break;
    const double y = map.discrete ? bar_top + bar_height * (1 - (v - map.low + 0.5) / (span + 1))
                                  : bar_top + bar_height * (1 - (v - map.low) / span);
    text(cr, bar_x + 26, y + 4, tick_label(v, step));
  }
  cairo_set_font_size(cr, 13);
  text(cr, bar_x, bar_top - 10, map.unit);
  canvas.save(png);
}

}  // namespace irloc::sim
