// A survey from above: the drawing, the estimate with its sigmas, the truth, the moves.

#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "host_sim/plots/canvas.hpp"

namespace irloc::sim {

using namespace drawing;
constexpr double kPi = std::numbers::pi;

namespace {

const Colour kEstimateColour{0.10, 0.35, 0.80}, kTruthColour{0.10, 0.60, 0.20}, kMovedColour{0.85, 0.10, 0.10};

// The drawing's markers as grey squares, a red line from each to its estimate where that moved
// farther than `move_threshold`, and the true markers as green crosses.
void draw_drawing_moves_and_truth(cairo_t* cr, const Axes& axes, const MarkerMap& drawing, const MarkerMap& estimate,
                                  const MarkerMap& true_map, double move_threshold) {
  cairo_set_line_width(cr, 1);
  set_colour(cr, kGrey);
  for (const DotMarker& marker : drawing.dot_markers) {
    cairo_rectangle(cr, axes.px(marker.origin.x()) - 6, axes.py(marker.origin.y()) - 6, 12, 12);
    cairo_stroke(cr);
  }
  for (const DotMarker& marker : estimate.dot_markers) {
    const DotMarker* drawn = drawing.find_dot_marker(marker.id);
    if (drawn == nullptr || (marker.origin - drawn->origin).head<2>().norm() <= move_threshold) continue;
    set_colour(cr, kMovedColour);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, axes.px(drawn->origin.x()), axes.py(drawn->origin.y()));
    cairo_line_to(cr, axes.px(marker.origin.x()), axes.py(marker.origin.y()));
    cairo_stroke(cr);
  }
  set_colour(cr, kTruthColour);
  cairo_set_line_width(cr, 2);
  for (const DotMarker& marker : true_map.dot_markers) {
    const double u = axes.px(marker.origin.x()), v = axes.py(marker.origin.y());
    cairo_move_to(cr, u - 7, v - 7);
    cairo_line_to(cr, u + 7, v + 7);
    cairo_move_to(cr, u - 7, v + 7);
    cairo_line_to(cr, u + 7, v - 7);
    cairo_stroke(cr);
  }
}

// Each estimated marker: a blue dot, its x/y sigma ellipse scaled by `sigma_scale`, its ID.
void draw_estimate(cairo_t* cr, const Axes& axes, const MarkerMap& estimate, double sigma_scale) {
  const double scale = axes.width / (axes.x1 - axes.x0);  // canvas pixels per metre
  for (const DotMarker& marker : estimate.dot_markers) {
    const double u = axes.px(marker.origin.x()), v = axes.py(marker.origin.y());
    set_colour(cr, kEstimateColour);
    cairo_arc(cr, u, v, 3, 0, 2 * kPi);
    cairo_fill(cr);
    if (marker.sigma) {
      const double rx = std::max(sigma_scale * (*marker.sigma)[0] * scale, 0.5);
      const double ry = std::max(sigma_scale * (*marker.sigma)[1] * scale, 0.5);
      cairo_save(cr);
      cairo_translate(cr, u, v);
      cairo_scale(cr, rx, ry);
      cairo_arc(cr, 0, 0, 1, 0, 2 * kPi);
      cairo_restore(cr);
      cairo_set_line_width(cr, 1.5);
      cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, u + 9, v - 9, std::to_string(marker.id) + (marker.fixed ? " (fixed)" : ""));
  }
}

}  // namespace

void plot_survey_map(const std::filesystem::path& png, const MarkerMap& drawing, const MarkerMap& estimate,
                     const MarkerMap* truth, double sigma_scale, double move_threshold) {
  const MarkerMap no_truth;
  const MarkerMap& true_map = truth != nullptr ? *truth : no_truth;
  TopViewExtent extent;
  for (const MarkerMap* map : {&drawing, &estimate, &true_map}) {
    for (const DotMarker& marker : map->dot_markers) extent.add(marker.origin.x(), marker.origin.y());
  }
  const Axes axes = extent.equal_axes(70, 40, 640, 0.1, 0.3);
  Canvas canvas(static_cast<int>(axes.width) + 300, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  axes.draw(cr, "x (m)", "y (m)",
            truth != nullptr ? "Survey: drawing, estimate and truth (top view)" : "Survey: before and after (top view)");
  draw_drawing_moves_and_truth(cr, axes, drawing, estimate, true_map, move_threshold);
  draw_estimate(cr, axes, estimate, sigma_scale);
  char sigma_label[64];
  std::snprintf(sigma_label, sizeof sigma_label, "estimate, 1-sigma x %.0f", sigma_scale);
  if (truth != nullptr) {
    legend(cr, axes.left + axes.width + 20, axes.top + 20,
           {{kGrey, "drawing (survey input)"}, {kEstimateColour, sigma_label}, {kTruthColour, "truth"},
            {kMovedColour, "moved"}});
  } else {
    legend(cr, axes.left + axes.width + 20, axes.top + 20,
           {{kGrey, "before (survey input)"}, {kEstimateColour, sigma_label}, {kMovedColour, "moved"}});
  }
  canvas.save(png);
}

}  // namespace irloc::sim
