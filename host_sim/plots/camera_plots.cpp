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

namespace {

// The timeline of the hand-over plot: one row per camera, the combined stream last; time in s
// from the first frame.
struct HandOverTimeline {
  Axes axes;
  double row_height;
  double frame_width;  // s
  std::int64_t t0_ns;

  double seconds(std::int64_t t_ns) const { return static_cast<double>(t_ns - t0_ns) * 1e-9; }
  double row_top(std::size_t row) const { return axes.top + static_cast<double>(row) * row_height; }
  // One frame's bar in a row, inset from the row's edges.
  void bar(cairo_t* cr, std::int64_t t_ns, std::size_t row, double inset) const {
    cairo_rectangle(cr, axes.px(seconds(t_ns) - frame_width / 2), row_top(row) + inset,
                    frame_width * axes.width / axes.x1 + 0.5, row_height - 2 * inset);
  }
};

// Each camera's ok poses where it has the robot whole in view: (time s, position error m).
std::vector<std::vector<std::pair<double, double>>> camera_errors(const std::vector<std::vector<OutsideInTruth>>& truth,
                                                                  const std::vector<std::vector<PoseEstimate>>& poses,
                                                                  const HandOverTimeline& timeline) {
  std::vector<std::vector<std::pair<double, double>>> errors(truth.size());
  for (std::size_t i = 0; i < truth.size(); ++i) {
    std::unordered_map<std::uint64_t, const OutsideInTruth*> by_seq;
    for (const OutsideInTruth& row : truth[i]) by_seq[row.pose.seq] = &row;
    for (const PoseEstimate& pose : poses[i]) {
      const auto found = by_seq.find(pose.seq);
      if (!pose.ok || found == by_seq.end()) continue;
      const double error = std::hypot(pose.x - found->second->pose.x, pose.y - found->second->pose.y);
      errors[i].emplace_back(timeline.seconds(pose.t_ns), error);
    }
  }
  return errors;
}

void draw_hand_over_rows(cairo_t* cr, const HandOverTimeline& timeline, const std::vector<std::vector<OutsideInTruth>>& truth,
                         const std::vector<std::vector<PoseEstimate>>& poses, const CameraHandOver& combined,
                         const std::vector<std::string>& names) {
  const std::size_t cameras = truth.size();
  const Axes& axes = timeline.axes;
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, axes.left, axes.top, axes.width, axes.height);
  cairo_stroke(cr);
  cairo_set_font_size(cr, 14);
  text(cr, axes.left + axes.width / 2, axes.top - 10, "Hand-over: robot whole in view (light), posed (dark)", 0.5);
  cairo_set_font_size(cr, 12);
  for (std::size_t i = 0; i <= cameras; ++i) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, axes.left - 8, timeline.row_top(i) + timeline.row_height / 2 + 4, i < cameras ? names[i] : "combined", 1);
  }
  for (std::size_t i = 0; i < cameras; ++i) {
    const Colour colour = camera_colour(i);
    set_colour(cr, lighter(colour, 0.7));
    for (const OutsideInTruth& row : truth[i]) {
      if (row.whole_in_view) timeline.bar(cr, row.pose.t_ns, i, 3);
    }
    cairo_fill(cr);
    set_colour(cr, colour);
    for (const PoseEstimate& pose : poses[i]) {
      if (pose.ok) timeline.bar(cr, pose.t_ns, i, 7);
    }
    cairo_fill(cr);
  }
  for (std::size_t frame = 0; frame < combined.truth.size(); ++frame) {
    const std::int64_t t_ns = combined.truth[frame].pose.t_ns;
    if (combined.truth[frame].whole_in_view) {
      set_colour(cr, {0.85, 0.85, 0.85});
      timeline.bar(cr, t_ns, cameras, 3);
      cairo_fill(cr);
    }
    if (combined.camera[frame] < 0) continue;
    set_colour(cr, camera_colour(static_cast<std::size_t>(combined.camera[frame])));
    timeline.bar(cr, t_ns, cameras, 7);
    cairo_fill(cr);
  }
}

}  // namespace

void plot_camera_handover(const std::filesystem::path& png, const std::vector<std::vector<OutsideInTruth>>& truth,
                          const std::vector<std::vector<PoseEstimate>>& poses, const CameraHandOver& combined,
                          const std::vector<std::string>& names, double gross_position) {
  const std::size_t cameras = truth.size();
  HandOverTimeline timeline{};
  timeline.t0_ns = combined.truth.empty() ? 0 : combined.truth.front().pose.t_ns;
  const double t_end = combined.truth.size() > 1 ? timeline.seconds(combined.truth.back().pose.t_ns) : 1;
  timeline.frame_width = combined.truth.size() > 1 ? t_end / static_cast<double>(combined.truth.size() - 1) : 1;
  timeline.row_height = 22;
  const double rows = static_cast<double>(cameras + 1);
  timeline.axes = Axes{120, 40, 600, rows * timeline.row_height, 0, t_end, 0, rows};
  // The error scale stops at the gross threshold (a worse pose is drawn on the top edge).
  const std::vector<std::vector<std::pair<double, double>>> errors = camera_errors(truth, poses, timeline);
  double error_max = 0.005;
  for (const auto& camera : errors) {
    for (const auto& [t, error] : camera) error_max = std::max(error_max, std::min(error, gross_position));
  }
  Canvas canvas(900, static_cast<int>(rows * timeline.row_height + 400));
  cairo_t* cr = canvas.cr();
  draw_hand_over_rows(cr, timeline, truth, poses, combined, names);
  const Axes& axes = timeline.axes;
  const Axes bottom{120, axes.top + axes.height + 70, 600, 220, 0, t_end, 0, error_max * 1e3 * 1.1};
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
  legend(cr, axes.left + axes.width + 20, bottom.top + 20, entries);
  char line[64];
  std::snprintf(line, sizeof line, "%d hand-overs", combined.hand_overs);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, axes.left + axes.width + 20, bottom.top + 30 + 18 * static_cast<double>(cameras), line);
  canvas.save(png);
}

namespace {

// A camera's footprint: the floor points of rays through the image border; a ray that meets the
// floor beyond `reach` (or above the horizon) is cut there.
std::vector<Eigen::Vector2d> camera_footprint(const WallCamera& camera, double reach) {
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
  return border;
}

// The room's axes: the path, the cameras and the reference rectangles, with equal scales.
Axes room_axes(const std::vector<WallCamera>& cameras, const std::vector<std::array<Eigen::Vector2d, 4>>& floor_references,
               const CameraHandOver& combined) {
  TopViewExtent extent;
  for (const OutsideInTruth& row : combined.truth) extent.add(row.pose.x, row.pose.y);
  for (const WallCamera& camera : cameras) extent.add(camera.position.x(), camera.position.y());
  for (const auto& reference : floor_references) {
    for (const Eigen::Vector2d& corner : reference) extent.add(corner.x(), corner.y());
  }
  return extent.equal_axes(70, 40, 600, 0.08);
}

// Shaded footprint and dashed floor reference of each camera.
void draw_footprints(cairo_t* cr, const Axes& axes, const std::vector<WallCamera>& cameras,
                     const std::vector<std::array<Eigen::Vector2d, 4>>& floor_references, double reach) {
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const Colour colour = camera_colour(i);
    const std::vector<Eigen::Vector2d> footprint = camera_footprint(cameras[i], reach);
    for (std::size_t p = 0; p < footprint.size(); ++p) {
      (p == 0 ? cairo_move_to : cairo_line_to)(cr, axes.px(footprint[p].x()), axes.py(footprint[p].y()));
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
}

// The true path, and each combined pose in the colour of the camera it came from.
void draw_path_and_poses(cairo_t* cr, const Axes& axes, const CameraHandOver& combined) {
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
}

// The cameras: a wedge pointing where each looks, and its name.
void draw_camera_wedges(cairo_t* cr, const Axes& axes, const std::vector<WallCamera>& cameras,
                        const std::vector<std::string>& names) {
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
}

}  // namespace

void plot_camera_room(const std::filesystem::path& png, const std::vector<WallCamera>& cameras,
                      const std::vector<std::array<Eigen::Vector2d, 4>>& floor_references, const CameraHandOver& combined,
                      const std::vector<std::string>& names, double reach) {
  const Axes axes = room_axes(cameras, floor_references, combined);
  Canvas canvas(static_cast<int>(axes.width) + 260, static_cast<int>(axes.height) + 100);
  cairo_t* cr = canvas.cr();
  axes.draw(cr, "x (m)", "y (m)", "Wall cameras: floor footprints, path and combined poses");
  cairo_save(cr);
  cairo_rectangle(cr, axes.left, axes.top, axes.width, axes.height);
  cairo_clip(cr);
  draw_footprints(cr, axes, cameras, floor_references, reach);
  draw_path_and_poses(cr, axes, combined);
  cairo_restore(cr);
  draw_camera_wedges(cr, axes, cameras, names);
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
