#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <unordered_map>

#include <cairo.h>

#include "algo/markers/dot/dot_marker_layout.hpp"
#include "host_sim/plots/png_file.hpp"

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
// One colour per wall camera (outside-in hand-over), cycled beyond eight.
constexpr Colour kCameraColours[] = {{0.12, 0.47, 0.71}, {0.89, 0.10, 0.11}, {0.20, 0.63, 0.17}, {0.60, 0.31, 0.64},
                                     {1.00, 0.50, 0.00}, {0.65, 0.34, 0.16}, {0.97, 0.51, 0.75}, {0.40, 0.40, 0.40}};
Colour camera_colour(std::size_t camera) { return kCameraColours[camera % std::size(kCameraColours)]; }
Colour lighter(Colour c, double amount) { return {c.r + amount * (1 - c.r), c.g + amount * (1 - c.g), c.b + amount * (1 - c.b)}; }

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
  void save(const std::filesystem::path& png) const { write_png(png, surface_); }

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
  cairo_new_path(cr);  // show_text leaves a current point: the next shape must not start from it
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
  // Each dot marker's ID goes right of its footprint, drawn last so that the path never hides it.
  std::vector<std::pair<Eigen::Vector2d, std::string>> labels;
  for (const DotMarker& marker : map.dot_markers) {
    // The marker's footprint: the centres of its corner cells O, X, (3, 3) and Y, a path of its own.
    cairo_new_path(cr);
    double right = -1e300, top = 1e300, bottom = -1e300;
    for (const int cell : {dot::kCellO, dot::kCellX, dot::cell_index(3, 3), dot::kCellY}) {
      const Eigen::Vector3d c = dot::cell_in_world(marker, cell);
      cairo_line_to(cr, axes.px(c.x()), axes.py(c.y()));
      right = std::max(right, axes.px(c.x()));
      top = std::min(top, axes.py(c.y()));
      bottom = std::max(bottom, axes.py(c.y()));
    }
    cairo_close_path(cr);
    cairo_fill(cr);
    labels.emplace_back(Eigen::Vector2d(right + 4, (top + bottom) / 2 + 4), std::to_string(marker.id));
  }
  for (const LedLandmark& landmark : map.led_landmarks) {
    cairo_new_sub_path(cr);
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
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  for (const auto& [at, id] : labels) text(cr, at.x(), at.y(), id);
  legend(cr, axes.left + axes.width + 20, axes.top + 20,
         {{kTruth, "truth"}, {kEstimate, "estimate (ok)"}, {kGross, "gross error"}, {{0.2, 0.2, 0.2}, "markers"}});
  char line[128];
  std::snprintf(line, sizeof line, "detection %.1f %%", 100 * metrics.detection_rate);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, axes.left + axes.width + 20, axes.top + 110, line);
  std::snprintf(line, sizeof line, "RMSE %.2f mm", metrics.position.rmse * 1e3);
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
  // Millimetres and degrees, the scales fitted to the largest error (a clean run's errors are
  // fractions of a millimetre: a fixed centimetre scale would show them as a flat line).
  double position_max = 0.5, yaw_max = 0.05;
  for (const PoseError& e : metrics.errors) {
    position_max = std::max(position_max, e.position * 1e3);
    yaw_max = std::max(yaw_max, e.yaw * 180 / kPi);
  }
  Canvas canvas(820, 560);
  cairo_t* cr = canvas.cr();
  const Axes top{80, 40, 600, 190, 0, t_end, 0, position_max * 1.1};
  const Axes bottom{80, 300, 600, 190, 0, t_end, 0, yaw_max * 1.1};
  top.draw(cr, "", "position error (mm)", "Error over time");
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
    cairo_arc(cr, top.px(e.t), top.py(e.position * 1e3), 2, 0, 2 * kPi);
    cairo_fill(cr);
    cairo_arc(cr, bottom.px(e.t), bottom.py(e.yaw * 180 / kPi), 2, 0, 2 * kPi);
    cairo_fill(cr);
  }
  legend(cr, 700, 60, {{kEstimate, "ok pose"}, {kGross, "gross error"}, {kGrey, "no pose"}});
  canvas.save(png);
}

void plot_camera_handover(const std::filesystem::path& png, const std::vector<std::vector<OutsideInTruth>>& truth,
                          const std::vector<std::vector<PoseEstimate>>& poses, const CameraHandOver& combined,
                          const std::vector<std::string>& names, double gross_position) {
  const std::size_t cameras = truth.size();
  const std::int64_t t0 = combined.truth.empty() ? 0 : combined.truth.front().pose.t_ns;
  const auto seconds = [t0](std::int64_t t_ns) { return static_cast<double>(t_ns - t0) * 1e-9; };
  const double t_end = combined.truth.size() > 1 ? seconds(combined.truth.back().pose.t_ns) : 1;
  const double frame_width = combined.truth.size() > 1 ? t_end / static_cast<double>(combined.truth.size() - 1) : 1;
  // Errors: each camera's ok poses where it has the robot whole in view; the scale stops at the
  // gross threshold (a worse pose is drawn on the top edge).
  std::vector<std::vector<std::pair<double, double>>> errors(cameras);
  double error_max = 0.005;
  for (std::size_t i = 0; i < cameras; ++i) {
    std::unordered_map<std::uint64_t, const OutsideInTruth*> by_seq;
    for (const OutsideInTruth& row : truth[i]) by_seq[row.pose.seq] = &row;
    for (const PoseEstimate& pose : poses[i]) {
      const auto found = by_seq.find(pose.seq);
      if (!pose.ok || found == by_seq.end()) continue;
      const double error = std::hypot(pose.x - found->second->pose.x, pose.y - found->second->pose.y);
      errors[i].emplace_back(seconds(pose.t_ns), error);
      error_max = std::max(error_max, std::min(error, gross_position));
    }
  }
  const double row_height = 22;
  const double rows = static_cast<double>(cameras + 1);
  Canvas canvas(900, static_cast<int>(rows * row_height + 400));
  cairo_t* cr = canvas.cr();
  const Axes timeline{120, 40, 600, rows * row_height, 0, t_end, 0, rows};
  const Axes bottom{120, timeline.top + timeline.height + 70, 600, 220, 0, t_end, 0, error_max * 1e3 * 1.1};
  // The timeline's rows: camera 0 at the top, the combined stream last.
  const auto row_top = [&](std::size_t row) { return timeline.top + static_cast<double>(row) * row_height; };
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, timeline.left, timeline.top, timeline.width, timeline.height);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 14);
  text(cr, timeline.left + timeline.width / 2, timeline.top - 10, "Hand-over: robot whole in view (light), posed (dark)", 0.5);
  cairo_set_font_size(cr, 12);
  for (std::size_t i = 0; i <= cameras; ++i) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, timeline.left - 8, row_top(i) + row_height / 2 + 4, i < cameras ? names[i] : "combined", 1);
  }
  for (std::size_t i = 0; i < cameras; ++i) {
    const Colour colour = camera_colour(i);
    set_colour(cr, lighter(colour, 0.7));
    for (const OutsideInTruth& row : truth[i]) {
      if (!row.whole_in_view) continue;
      cairo_rectangle(cr, timeline.px(seconds(row.pose.t_ns) - frame_width / 2), row_top(i) + 3,
                      frame_width * timeline.width / t_end + 0.5, row_height - 6);
    }
    cairo_fill(cr);
    set_colour(cr, colour);
    for (const PoseEstimate& pose : poses[i]) {
      if (!pose.ok) continue;
      cairo_rectangle(cr, timeline.px(seconds(pose.t_ns) - frame_width / 2), row_top(i) + 7,
                      frame_width * timeline.width / t_end + 0.5, row_height - 14);
    }
    cairo_fill(cr);
  }
  for (std::size_t frame = 0; frame < combined.truth.size(); ++frame) {
    const double t = seconds(combined.truth[frame].pose.t_ns);
    if (combined.truth[frame].whole_in_view) {
      set_colour(cr, {0.85, 0.85, 0.85});
      cairo_rectangle(cr, timeline.px(t - frame_width / 2), row_top(cameras) + 3, frame_width * timeline.width / t_end + 0.5,
                      row_height - 6);
      cairo_fill(cr);
    }
    if (combined.camera[frame] < 0) continue;
    set_colour(cr, camera_colour(static_cast<std::size_t>(combined.camera[frame])));
    cairo_rectangle(cr, timeline.px(t - frame_width / 2), row_top(cameras) + 7, frame_width * timeline.width / t_end + 0.5,
                    row_height - 14);
    cairo_fill(cr);
  }
  bottom.draw(cr, "time (s)", "position error (mm)", "Each camera's position error");
  for (std::size_t i = 0; i < cameras; ++i) {
    set_colour(cr, camera_colour(i));
    for (const auto& [t, error] : errors[i]) {
      cairo_arc(cr, bottom.px(t), bottom.py(std::min(error, gross_position) * 1e3), 2, 0, 2 * kPi);
      cairo_fill(cr);
    }
  }
  std::vector<std::pair<Colour, std::string>> entries;
  for (std::size_t i = 0; i < cameras; ++i) entries.emplace_back(camera_colour(i), names[i]);
  legend(cr, timeline.left + timeline.width + 20, bottom.top + 20, entries);
  char line[64];
  std::snprintf(line, sizeof line, "%d hand-overs", combined.hand_overs);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, timeline.left + timeline.width + 20, bottom.top + 30 + 18 * static_cast<double>(cameras), line);
  canvas.save(png);
}

void plot_camera_room(const std::filesystem::path& png, const std::vector<WallCamera>& cameras,
                      const std::vector<std::array<Eigen::Vector2d, 4>>& floor_references, const CameraHandOver& combined,
                      const std::vector<std::string>& names, double reach) {
  // Each camera's footprint: the floor points of rays through the image border; a ray that
  // meets the floor beyond `reach` (or above the horizon) is cut there.
  std::vector<std::vector<Eigen::Vector2d>> footprints;
  for (const WallCamera& camera : cameras) {
    const RigidTransform pose = camera.world_from_camera();
    const Eigen::Vector2d foot = pose.translation.head<2>();
    const auto& k = camera.intrinsics;
    std::vector<Eigen::Vector2d> border;
    constexpr int kSteps = 24;
    for (int side = 0; side < 4; ++side) {
      for (int step = 0; step < kSteps; ++step) {
        const double f = static_cast<double>(step) / kSteps;
        const double u = side == 0 ? f * k.width : side == 1 ? k.width : side == 2 ? (1 - f) * k.width : 0;
        const double v = side == 0 ? 0 : side == 1 ? f * k.height : side == 2 ? k.height : (1 - f) * k.height;
        const Eigen::Vector3d ray = pose.rotation * Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1);
        const Eigen::Vector2d flat = ray.head<2>().normalized();
        Eigen::Vector2d point = foot + reach * flat;
        if (ray.z() < 0) {
          const Eigen::Vector2d hit = (pose.translation + (-pose.translation.z() / ray.z()) * ray).head<2>();
          if ((hit - foot).norm() < reach) point = hit;
        }
        border.push_back(point);
      }
    }
    footprints.push_back(border);
  }
  // Extent: the path, the cameras and the reference rectangles, with equal scales.
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  const auto extend = [&](const Eigen::Vector2d& p) {
    x0 = std::min(x0, p.x()); x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y()); y1 = std::max(y1, p.y());
  };
  for (const OutsideInTruth& row : combined.truth) extend({row.pose.x, row.pose.y});
  for (const WallCamera& camera : cameras) extend(camera.position);
  for (const auto& reference : floor_references) {
    for (const Eigen::Vector2d& corner : reference) extend(corner);
  }
  if (x0 > x1) { x0 = y0 = -1; x1 = y1 = 1; }
  const double margin = 0.08 * std::max({x1 - x0, y1 - y0, 0.5});
  x0 -= margin; x1 += margin; y0 -= margin; y1 += margin;
  const double scale = 600 / std::max(x1 - x0, y1 - y0);
  const Axes axes{70, 40, (x1 - x0) * scale, (y1 - y0) * scale, x0, x1, y0, y1};
  Canvas canvas(static_cast<int>(axes.width) + 260, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  axes.draw(cr, "x (m)", "y (m)", "Wall cameras: floor footprints, path and combined poses");
  cairo_save(cr);
  cairo_rectangle(cr, axes.left, axes.top, axes.width, axes.height);
  cairo_clip(cr);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const Colour colour = camera_colour(i);
    for (std::size_t p = 0; p < footprints[i].size(); ++p) {
      (p == 0 ? cairo_move_to : cairo_line_to)(cr, axes.px(footprints[i][p].x()), axes.py(footprints[i][p].y()));
    }
    cairo_close_path(cr);
    cairo_set_source_rgba(cr, colour.r, colour.g, colour.b, 0.12);
    cairo_fill_preserve(cr);
    set_colour(cr, colour);
    cairo_set_line_width(cr, 1.5);
    cairo_stroke(cr);
    const auto& reference = floor_references[i];
    for (std::size_t c = 0; c <= 4; ++c) {
      (c == 0 ? cairo_move_to : cairo_line_to)(cr, axes.px(reference[c % 4].x()), axes.py(reference[c % 4].y()));
    }
    const double dashes[] = {5, 3};
    cairo_set_dash(cr, dashes, 2, 0);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  set_colour(cr, {0.3, 0.3, 0.3});
  cairo_set_line_width(cr, 1.5);
  for (std::size_t frame = 0; frame < combined.truth.size(); ++frame) {
    (frame == 0 ? cairo_move_to : cairo_line_to)(cr, axes.px(combined.truth[frame].pose.x), axes.py(combined.truth[frame].pose.y));
  }
  cairo_stroke(cr);
  for (std::size_t frame = 0; frame < combined.poses.size(); ++frame) {
    if (combined.camera[frame] < 0) continue;
    set_colour(cr, camera_colour(static_cast<std::size_t>(combined.camera[frame])));
    cairo_arc(cr, axes.px(combined.poses[frame].x), axes.py(combined.poses[frame].y), 2.5, 0, 2 * kPi);
    cairo_fill(cr);
  }
  cairo_restore(cr);
  // The cameras: a wedge pointing where each looks, and its name.
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const double yaw = cameras[i].yaw_deg * kPi / 180;
    const double cx = axes.px(cameras[i].position.x()), cy = axes.py(cameras[i].position.y());
    set_colour(cr, camera_colour(i));
    cairo_move_to(cr, cx + 14 * std::cos(yaw), cy - 14 * std::sin(yaw));
    cairo_line_to(cr, cx + 7 * std::cos(yaw + 2.3), cy - 7 * std::sin(yaw + 2.3));
    cairo_line_to(cr, cx + 7 * std::cos(yaw - 2.3), cy - 7 * std::sin(yaw - 2.3));
    cairo_close_path(cr);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, cx + 10, cy + 18, names[i]);
  }
  std::vector<std::pair<Colour, std::string>> entries;
  for (std::size_t i = 0; i < cameras.size(); ++i) entries.emplace_back(camera_colour(i), names[i] + " (its poses)");
  entries.emplace_back(Colour{0.3, 0.3, 0.3}, "true path");
  legend(cr, axes.left + axes.width + 20, axes.top + 20, entries);
  cairo_set_source_rgb(cr, 0, 0, 0);
  const double below = axes.top + 40 + 18 * static_cast<double>(entries.size());
  text(cr, axes.left + axes.width + 20, below, "shaded: footprint");
  text(cr, axes.left + axes.width + 20, below + 18, "dashed: floor reference");
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
