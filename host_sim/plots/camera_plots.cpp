// Outside-in with several wall cameras: the hand-over along time and the room from above.

#include "host_sim/plots/plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <unordered_map>

#include "host_sim/plots/canvas.hpp"

namespace irloc::sim {

using namespace drawing;
constexpr double kPi = std::numbers::pi;

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

}  // namespace irloc::sim
