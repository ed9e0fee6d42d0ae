// A run against its truth: the top view (trajectory.png) and the errors over time (errors.png).

#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>
#include <numbers>

#include "algo/markers/dot/dot_marker_layout.hpp"
#include "host_sim/plots/canvas.hpp"

namespace irloc::sim {

using namespace drawing;
constexpr double kPi = std::numbers::pi;

namespace {

// The map's markers in grey: squares outlined, dot markers as their footprints, LEDs as discs.
// Returns each dot marker's ID label, to go right of its footprint and be drawn last, so that
// the path never hides it.
std::vector<std::pair<Eigen::Vector2d, std::string>> draw_markers(cairo_t* cr, const Axes& axes, const MarkerMap& map) {
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
  return labels;
}

}  // namespace

void plot_trajectory(const std::filesystem::path& png, const std::vector<TruthRow>& truth,
                     const std::vector<PoseEstimate>& poses, const Metrics& metrics, const MarkerMap& map) {
  // Data extent: the path, the estimates and the markers, with equal scales on both axes.
  TopViewExtent extent;
  for (const TruthRow& row : truth) extent.add(row.x, row.y);
  for (const DotMarker& marker : map.dot_markers) extent.add(marker.origin.x(), marker.origin.y());
  for (const SquareMarker& marker : map.square_markers) {
    for (const auto& corner : marker.corners) extent.add(corner.x(), corner.y());
  }
  for (const LedLandmark& landmark : map.led_landmarks) extent.add(landmark.position.x(), landmark.position.y());
  const Axes axes = extent.equal_axes(70, 40, 520, 0.1);
  Canvas canvas(static_cast<int>(axes.width) + 260, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  axes.draw(cr, "x (m)", "y (m)", "Trajectory: truth and estimate (top view)");

  const std::vector<std::pair<Eigen::Vector2d, std::string>> labels = draw_markers(cr, axes, map);

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

}  // namespace irloc::sim
