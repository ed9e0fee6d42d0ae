#include "host_sim/plots/debug_frames.hpp"

#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <numbers>
#include <vector>

#include "io/input_error.hpp"
#include "io/dataset/pgm.hpp"
#include "host_sim/plots/png_file.hpp"
#include "host_sim/render/ceiling_layout.hpp"
#include "host_sim/render/marker_view.hpp"

namespace irloc::sim {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Isometry3d pose_matrix(double x, double y, double z, double roll, double pitch, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation_from_rpy(roll, pitch, yaw);
  t.translation() = Eigen::Vector3d(x, y, z);
  return t;
}

// World points standing for the map: every dot centre, tape centre-lines every 10 cm, landmarks.
std::vector<Eigen::Vector3d> map_points(const MarkerMap& map) {
  std::vector<Eigen::Vector3d> points;
  for (const DotMarker& marker : map.dot_markers) {
    for (const Eigen::Vector3d& centre : CeilingLayout::dot_centres(marker)) points.push_back(centre);
  }
  for (const SquareMarker& marker : map.square_markers) {
    for (std::size_t side = 0; side < 4; ++side) {
      const Eigen::Vector3d& a = marker.corners[side];
      const Eigen::Vector3d& b = marker.corners[(side + 1) % 4];
      const int steps = std::max(1, static_cast<int>((b - a).norm() / 0.1));
      for (int i = 0; i < steps; ++i) points.push_back(a + (b - a) * (static_cast<double>(i) / steps));
    }
  }
  for (const LedLandmark& landmark : map.led_landmarks) points.push_back(landmark.position);
  return points;
}

// The frame as an RGB cairo surface (16-bit frames scaled to 8 bits for display).
cairo_surface_t* load_frame(const std::filesystem::path& pgm) {
  std::ifstream in(pgm, std::ios::binary);
  if (!in) throw io::InputError(pgm.string() + ": cannot open");
  std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(chars.data()), chars.size());
  const io::PgmHeader header = io::parse_pgm_header(bytes, pgm.string());
  if (header.pixel_offset + header.pixel_bytes() > bytes.size()) throw io::InputError(pgm.string() + ": truncated");
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, header.width, header.height);
  cairo_surface_flush(surface);
  unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const auto* pixels = reinterpret_cast<const unsigned char*>(bytes.data() + header.pixel_offset);
  for (int y = 0; y < header.height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 0; x < header.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(header.width) + static_cast<std::size_t>(x);
      const unsigned value = header.bytes_per_pixel() == 1 ? pixels[i] : (pixels[2 * i] << 8u | pixels[2 * i + 1]);
      const auto grey = static_cast<std::uint32_t>(value * 255u / static_cast<unsigned>(header.maxval));
      row[x] = grey << 16 | grey << 8 | grey;
    }
  }
  cairo_surface_mark_dirty(surface);
  return surface;
}

}  // namespace

namespace {

// The frame under its banner, scaled so that a small frame stays readable.
struct DebugCanvas {
  double scale;
  int banner;
  // Pixel centres are at integer coordinates; cairo's are at +0.5.
  Eigen::Vector2d at(const Eigen::Vector2d& pixel) const {
    return Eigen::Vector2d((pixel.x() + 0.5) * scale, (pixel.y() + 0.5) * scale + banner);
  }
};

// Green rings where the map's points project at the true pose, red crosses where they project at
// the estimate: thin and translucent, so the rendered markers stay visible under them.
void draw_projections(cairo_t* cr, const DebugCanvas& canvas, const CameraModel& camera, const Eigen::Isometry3d& t_b_c,
                      const MarkerMap& map, const TruthRow& truth, const PoseEstimate& estimate) {
  const std::vector<Eigen::Vector3d> points = map_points(map);
  cairo_set_line_width(cr, 1);
  cairo_set_source_rgba(cr, 0.2, 0.9, 0.3, 0.7);
  for (const ProjectedPoint& p :
       project_points(camera, pose_matrix(truth.x, truth.y, truth.z, truth.roll, truth.pitch, truth.yaw), t_b_c, points)) {
    if (!p.visible) continue;
    const Eigen::Vector2d c = canvas.at(p.pixel);
    cairo_new_sub_path(cr);
    cairo_arc(cr, c.x(), c.y(), 3 * canvas.scale + 3, 0, 2 * kPi);
  }
  cairo_stroke(cr);
  if (!estimate.ok) return;
  cairo_set_source_rgba(cr, 1.0, 0.25, 0.2, 0.8);
  const Eigen::Isometry3d t_w_b = pose_matrix(estimate.x, estimate.y, estimate.z, estimate.roll, estimate.pitch, estimate.yaw);
  for (const ProjectedPoint& p : project_points(camera, t_w_b, t_b_c, points)) {
    if (!p.visible) continue;
    const Eigen::Vector2d c = canvas.at(p.pixel);
    cairo_move_to(cr, c.x() - 3, c.y() - 3);
    cairo_line_to(cr, c.x() + 3, c.y() + 3);
    cairo_move_to(cr, c.x() - 3, c.y() + 3);
    cairo_line_to(cr, c.x() + 3, c.y() - 3);
  }
  cairo_stroke(cr);
}

// The banner's two lines: the frame and the legend, then the pose and its error.
void draw_banner(cairo_t* cr, const TruthRow& truth, const PoseEstimate& estimate) {
  char line1[160], line2[160];
  std::snprintf(line1, sizeof line1, "seq %llu  t %.3f s  LED %s   green o: markers at the true pose   red x: at the estimate",
                static_cast<unsigned long long>(truth.seq), static_cast<double>(truth.t_ns) * 1e-9, truth.led_on ? "on" : "off");
  if (estimate.ok) {
    const double error = std::hypot(estimate.x - truth.x, estimate.y - truth.y);
    std::snprintf(line2, sizeof line2, "pose ok  source %s  marker %d  confidence %.2f  error %.1f mm  %.2f deg",
                  std::string(to_string(estimate.source)).c_str(), estimate.marker_id, estimate.confidence, error * 1e3,
                  std::abs(wrap_angle(estimate.yaw - truth.yaw)) * 180 / kPi);
  } else {
    std::snprintf(line2, sizeof line2, "pose none (no trustworthy pose from this frame)");
  }
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12);
  cairo_move_to(cr, 6, 17);
  cairo_show_text(cr, line1);
  cairo_move_to(cr, 6, 36);
  cairo_show_text(cr, line2);
}

}  // namespace

void write_debug_frame(const std::filesystem::path& png, const std::filesystem::path& pgm, const CameraModel& camera,
                       const Eigen::Isometry3d& t_b_c, const MarkerMap& map, const TruthRow& truth,
                       const PoseEstimate& estimate) {
  cairo_surface_t* frame = load_frame(pgm);
  const int width = cairo_image_surface_get_width(frame), height = cairo_image_surface_get_height(frame);
  const DebugCanvas canvas{width < 480 ? 2.0 : 1.0, 44};
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(width * canvas.scale),
                                                        static_cast<int>(height * canvas.scale) + canvas.banner);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_paint(cr);
  cairo_save(cr);
  cairo_translate(cr, 0, canvas.banner);
  cairo_scale(cr, canvas.scale, canvas.scale);
  cairo_set_source_surface(cr, frame, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint(cr);
  cairo_restore(cr);
  draw_projections(cr, canvas, camera, t_b_c, map, truth, estimate);
  draw_banner(cr, truth, estimate);
  cairo_destroy(cr);
  cairo_surface_destroy(frame);
  try {
    write_png(png, surface);
  } catch (...) {
    cairo_surface_destroy(surface);
    throw;
  }
  cairo_surface_destroy(surface);
}

}  // namespace irloc::sim
