#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <unordered_map>

#include <cairo.h>

#include "algo/markers/dot/dot_marker_layout.hpp"
#include "hal/input_error.hpp"

namespace irloc::sim {
namespace {

constexpr double kPi = std::numbers::pi;

struct Colour {
  double r, g, b;
};
constexpr Colour kTruth{0.10, 0.35, 0.80};
constexpr Colour kEstimate{0.85, 0.20, 0.10};
constexpr Colour kGross{0.95, 0.65, 0.0};
constexpr Colour kGrey{0.55, 0.55, 0.55};

// Owns a cairo image surface and context; writes the PNG on save().
class Canvas {
 public:
  Canvas(int width, int height)
      : surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)), cr_(cairo_create(surface_)) {
    cairo_set_source_rgb(cr_, 1, 1, 1);
    cairo_paint(cr_);
    cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr_, 13);
  }
  ~Canvas() {
    cairo_destroy(cr_);
    cairo_surface_destroy(surface_);
  }
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  void save(const std::filesystem::path& png) const {
    if (cairo_surface_write_to_png(surface_, png.c_str()) != CAIRO_STATUS_SUCCESS) {
      throw hal::InputError(png.string() + ": cannot write the PNG");
    }
  }

 private:
  cairo_surface_t* surface_;
  cairo_t* cr_;
};

void set_colour(cairo_t* cr, Colour c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void text(cairo_t* cr, double x, double y, const std::string& label, double align = 0) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, label.c_str(), &extents);
  cairo_move_to(cr, x - align * extents.width, y);
  cairo_show_text(cr, label.c_str());
}

// A tick spacing of 1, 2 or 5 x 10^n giving about `count` ticks over `span`.
double nice_step(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10 * power;
}

std::string tick_label(double value, double step) {
  char label[32];
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  std::snprintf(label, sizeof label, "%.*f", decimals, std::abs(value) < step * 1e-6 ? 0.0 : value);
  return label;
}

// A plot area mapping data (x, y) to canvas pixels, with axes, ticks and labels.
struct Axes {
  double left, top, width, height;  // canvas pixels
  double x0, x1, y0, y1;            // data range

  double px(double x) const { return left + (x - x0) / (x1 - x0) * width; }
  double py(double y) const { return top + height - (y - y0) / (y1 - y0) * height; }

  // Grid lines are left out over images (heat maps).
  void draw(cairo_t* cr, const std::string& x_label, const std::string& y_label, const std::string& title,
            bool grid = true) const {
    cairo_set_line_width(cr, 1);
    cairo_set_source_rgb(cr, 0.92, 0.92, 0.92);
    const double x_step = nice_step(x1 - x0, 6), y_step = nice_step(y1 - y0, 5);
    for (double x = std::ceil(x0 / x_step) * x_step; x <= x1 + 1e-9; x += x_step) {
      cairo_move_to(cr, px(x), top);
      cairo_line_to(cr, px(x), top + height);
    }
    for (double y = std::ceil(y0 / y_step) * y_step; y <= y1 + 1e-9; y += y_step) {
      cairo_move_to(cr, left, py(y));
      cairo_line_to(cr, left + width, py(y));
    }
    if (grid) {
      cairo_stroke(cr);
    } else {
      cairo_new_path(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, left, top, width, height);
    cairo_stroke(cr);
    cairo_set_font_size(cr, 11);
    for (double x = std::ceil(x0 / x_step) * x_step; x <= x1 + 1e-9; x += x_step) {
      text(cr, px(x), top + height + 15, tick_label(x, x_step), 0.5);
    }
    for (double y = std::ceil(y0 / y_step) * y_step; y <= y1 + 1e-9; y += y_step) {
      text(cr, left - 6, py(y) + 4, tick_label(y, y_step), 1);
    }
    cairo_set_font_size(cr, 13);
    text(cr, left + width / 2, top + height + 34, x_label, 0.5);
    cairo_save(cr);
    cairo_translate(cr, left - 42, top + height / 2);
    cairo_rotate(cr, -kPi / 2);
    text(cr, 0, 0, y_label, 0.5);
    cairo_restore(cr);
    cairo_set_font_size(cr, 14);
    text(cr, left + width / 2, top - 10, title, 0.5);
    cairo_set_font_size(cr, 13);
  }
};

void legend(cairo_t* cr, double x, double y, const std::vector<std::pair<Colour, std::string>>& entries) {
  for (const auto& [colour, label] : entries) {
    set_colour(cr, colour);
    cairo_rectangle(cr, x, y - 9, 14, 10);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, x + 20, y, label);
    y += 18;
  }
}

// Perceptual-ish colour scale from dark blue through green to yellow, t in [0, 1].
Colour colour_scale(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const Colour stops[] = {{0.05, 0.03, 0.35}, {0.15, 0.35, 0.65}, {0.13, 0.65, 0.55}, {0.55, 0.82, 0.25}, {0.99, 0.91, 0.15}};
  const double position = t * 4;
  const int i = std::min(3, static_cast<int>(position));
  const double f = position - i;
  const Colour& a = stops[i];
  const Colour& b = stops[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b)};
}

}  // namespace

void plot_trajectory(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                     const std::vector<PoseEstimate>& poses, const Metrics& metrics, const MarkerMap& map) {
  // Data extent: the path, the estimates and the markers, with equal scales on both axes.
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const auto extend = [&](double x, double y) {
    x0 = std::min(x0, x); x1 = std::max(x1, x);
    y0 = std::min(y0, y); y1 = std::max(y1, y);
  };
  for (const TruthRow& row : truth) extend(row.x, row.y);
  for (const DotMarker& marker : map.dot_markers) extend(marker.origin.x(), marker.origin.y());
  for (const SquareMarker& marker : map.square_markers) {
    for (const auto& corner : marker.corners) extend(corner.x(), corner.y());
  }
  for (const LedLandmark& landmark : map.led_landmarks) extend(landmark.position.x(), landmark.position.y());
  if (x0 > x1) { x0 = y0 = -1; x1 = y1 = 1; }
  const double margin = 0.1 * std::max({x1 - x0, y1 - y0, 0.5});
  x0 -= margin; x1 += margin; y0 -= margin; y1 += margin;
  const double plot = 520;
  const double scale = plot / std::max(x1 - x0, y1 - y0);
  const Axes axes{70, 40, (x1 - x0) * scale, (y1 - y0) * scale, x0, x1, y0, y1};
  Canvas canvas(static_cast<int>(axes.width) + 260, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  axes.draw(cr, "x (m)", "y (m)", "Trajectory: truth and estimate (top view)");

  // Markers.
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_line_width(cr, 1.5);
  for (const SquareMarker& marker : map.square_markers) {
    cairo_move_to(cr, axes.px(marker.corners[0].x()), axes.py(marker.corners[0].y()));
    for (int i = 1; i <= 4; ++i) {
      const auto& c = marker.corners[static_cast<std::size_t>(i % 4)];
      cairo_line_to(cr, axes.px(c.x()), axes.py(c.y()));
    }
    cairo_stroke(cr);
  }
  for (const DotMarker& marker : map.dot_markers) {
    // The marker's footprint: the centres of its corner cells O, X, (3, 3) and Y.
    for (const int cell : {dot::kCellO, dot::kCellX, dot::cell_index(3, 3), dot::kCellY}) {
      const Eigen::Vector3d c = dot::cell_in_world(marker, cell);
      cairo_line_to(cr, axes.px(c.x()), axes.py(c.y()));
    }
    const Eigen::Vector2d o(marker.origin.x(), marker.origin.y());
    cairo_close_path(cr);
    cairo_fill(cr);
    text(cr, axes.px(o.x()) + 8, axes.py(o.y()) - 8, std::to_string(marker.id));
  }
  for (const LedLandmark& landmark : map.led_landmarks) {
    cairo_arc(cr, axes.px(landmark.position.x()), axes.py(landmark.position.y()), 4, 0, 2 * kPi);
    cairo_fill(cr);
  }

  // The true path.
  set_colour(cr, kTruth);
  cairo_set_line_width(cr, 2);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    (i == 0 ? cairo_move_to : cairo_line_to)(cr, axes.px(truth[i].x), axes.py(truth[i].y));
  }
  cairo_stroke(cr);

  // Estimates, gross errors in their own colour.
  std::unordered_map<std::uint64_t, bool> gross;
  for (const PoseError& error : metrics.errors) gross[error.seq] = error.gross;
  for (const PoseEstimate& pose : poses) {
    if (!pose.ok) continue;
    set_colour(cr, gross[pose.seq] ? kGross : kEstimate);
    cairo_arc(cr, axes.px(pose.x), axes.py(pose.y), 2.5, 0, 2 * kPi);
    cairo_fill(cr);
  }
  legend(cr, axes.left + axes.width + 20, axes.top + 20,
         {{kTruth, "truth"}, {kEstimate, "estimate (ok)"}, {kGross, "gross error"}, {{0.2, 0.2, 0.2}, "markers"}});
  char line[128];
  std::snprintf(line, sizeof line, "detection %.1f %%", 100 * metrics.detection_rate);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, axes.left + axes.width + 20, axes.top + 110, line);
  std::snprintf(line, sizeof line, "RMSE %.3f m", metrics.position.rmse);
  text(cr, axes.left + axes.width + 20, axes.top + 128, line);
  canvas.save(png);
}

void plot_survey_map(const std::filesystem::path& png, const MarkerMap& drawing, const MarkerMap& estimate,
                     const MarkerMap* truth, double sigma_scale, double move_threshold) {
  const MarkerMap no_truth;
  const MarkerMap& true_map = truth != nullptr ? *truth : no_truth;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const MarkerMap* map : {&drawing, &estimate, &true_map}) {
    for (const DotMarker& marker : map->dot_markers) {
      x0 = std::min(x0, marker.origin.x()); x1 = std::max(x1, marker.origin.x());
      y0 = std::min(y0, marker.origin.y()); y1 = std::max(y1, marker.origin.y());
    }
  }
  if (x0 > x1) { x0 = y0 = -1; x1 = y1 = 1; }
  const double margin = 0.1 * std::max({x1 - x0, y1 - y0, 0.5}) + 0.3;
  x0 -= margin; x1 += margin; y0 -= margin; y1 += margin;
  const double scale = 640 / std::max(x1 - x0, y1 - y0);
  const Axes axes{70, 40, (x1 - x0) * scale, (y1 - y0) * scale, x0, x1, y0, y1};
  Canvas canvas(static_cast<int>(axes.width) + 300, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  axes.draw(cr, "x (m)", "y (m)",
            truth != nullptr ? "Survey: drawing, estimate and truth (top view)" : "Survey: before and after (top view)");
  const Colour estimate_colour{0.10, 0.35, 0.80}, truth_colour{0.10, 0.60, 0.20}, moved_colour{0.85, 0.10, 0.10};

  cairo_set_line_width(cr, 1);
  set_colour(cr, kGrey);
  for (const DotMarker& marker : drawing.dot_markers) {
    cairo_rectangle(cr, axes.px(marker.origin.x()) - 6, axes.py(marker.origin.y()) - 6, 12, 12);
    cairo_stroke(cr);
  }
  for (const DotMarker& marker : estimate.dot_markers) {
    const DotMarker* drawn = drawing.find_dot_marker(marker.id);
    if (drawn == nullptr || (marker.origin - drawn->origin).head<2>().norm() <= move_threshold) continue;
    set_colour(cr, moved_colour);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, axes.px(drawn->origin.x()), axes.py(drawn->origin.y()));
    cairo_line_to(cr, axes.px(marker.origin.x()), axes.py(marker.origin.y()));
    cairo_stroke(cr);
  }
  set_colour(cr, truth_colour);
  cairo_set_line_width(cr, 2);
  for (const DotMarker& marker : true_map.dot_markers) {
    const double u = axes.px(marker.origin.x()), v = axes.py(marker.origin.y());
    cairo_move_to(cr, u - 7, v - 7);
    cairo_line_to(cr, u + 7, v + 7);
    cairo_move_to(cr, u - 7, v + 7);
    cairo_line_to(cr, u + 7, v - 7);
    cairo_stroke(cr);
  }
  for (const DotMarker& marker : estimate.dot_markers) {
    const double u = axes.px(marker.origin.x()), v = axes.py(marker.origin.y());
    set_colour(cr, estimate_colour);
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
  char sigma_label[64];
  std::snprintf(sigma_label, sizeof sigma_label, "estimate, 1-sigma x %.0f", sigma_scale);
  if (truth != nullptr) {
    legend(cr, axes.left + axes.width + 20, axes.top + 20,
           {{kGrey, "drawing (survey input)"}, {estimate_colour, sigma_label}, {truth_colour, "truth"},
            {moved_colour, "moved"}});
  } else {
    legend(cr, axes.left + axes.width + 20, axes.top + 20,
           {{kGrey, "before (survey input)"}, {estimate_colour, sigma_label}, {moved_colour, "moved"}});
  }
  canvas.save(png);
}

void plot_errors(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                 const std::vector<PoseEstimate>& poses, const Metrics& metrics) {
  const double t_end = truth.size() > 1 ? static_cast<double>(truth.back().t_ns - truth.front().t_ns) * 1e-9 : 1;
  double position_max = 0.01, yaw_max = 0.5;
  for (const PoseError& e : metrics.errors) {
    position_max = std::max(position_max, e.position);
    yaw_max = std::max(yaw_max, e.yaw * 180 / kPi);
  }
  Canvas canvas(820, 560);
  cairo_t* cr = canvas.cr();
  const Axes top{80, 40, 600, 190, 0, t_end, 0, position_max * 1.1};
  const Axes bottom{80, 300, 600, 190, 0, t_end, 0, yaw_max * 1.1};
  top.draw(cr, "", "position error (m)", "Error over time");
  bottom.draw(cr, "time (s)", "yaw error (deg)", "");

  // Frames whose attempt gave no pose: grey ticks along the bottom of both panels.
  const std::int64_t t0 = truth.empty() ? 0 : truth.front().t_ns;
  set_colour(cr, kGrey);
  cairo_set_line_width(cr, 1);
  for (const PoseEstimate& pose : poses) {
    if (pose.ok) continue;
    const double t = static_cast<double>(pose.t_ns - t0) * 1e-9;
    for (const Axes* axes : {&top, &bottom}) {
      cairo_move_to(cr, axes->px(t), axes->top + axes->height);
      cairo_line_to(cr, axes->px(t), axes->top + axes->height - 8);
    }
  }
  cairo_stroke(cr);
  for (const PoseError& e : metrics.errors) {
    set_colour(cr, e.gross ? kGross : kEstimate);
    cairo_arc(cr, top.px(e.t), top.py(e.position), 2, 0, 2 * kPi);
    cairo_fill(cr);
    cairo_arc(cr, bottom.px(e.t), bottom.py(e.yaw * 180 / kPi), 2, 0, 2 * kPi);
    cairo_fill(cr);
  }
  legend(cr, 700, 60, {{kEstimate, "ok pose"}, {kGross, "gross error"}, {kGrey, "no pose"}});
  canvas.save(png);
}

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
  for (double v = std::ceil(map.low / step) * step; v <= map.high + 1e-9; v += step) {
    const double y = map.discrete ? bar_top + bar_height * (1 - (v - map.low + 0.5) / (span + 1))
                                  : bar_top + bar_height * (1 - (v - map.low) / span);
    text(cr, bar_x + 26, y + 4, tick_label(v, step));
  }
  cairo_set_font_size(cr, 13);
  text(cr, bar_x, bar_top - 10, map.unit);
  canvas.save(png);
}

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
