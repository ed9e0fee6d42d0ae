#include "firmware/live/live_drawing.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <string>

#include "algo/geometry/pose.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/markers/outside_in/outside_in_source.hpp"

namespace irloc::firmware {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kBannerHeight = 40;
// The difference of a pair is far below the frame's full scale: shown four times brighter.
constexpr int kDifferenceGain = 4;

struct Colour {
  double r, g, b;
};
constexpr Colour kBlobColour{0.6, 0.6, 0.6};
constexpr Colour kDotColour{0.2, 0.95, 0.3};
constexpr Colour kReprojectedColour{1.0, 0.25, 0.2};
constexpr Colour kSquareColour{1.0, 0.9, 0.1};
constexpr Colour kLedColour{0.2, 0.9, 1.0};
constexpr Colour kMapColour{0.95, 0.3, 0.95};
constexpr Colour kBoxColour{1.0, 0.6, 0.1};

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void set_colour(cairo_t* cr, Colour c, double alpha = 1) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

// The frame (or the difference) as an RGB24 surface of the camera's size.
SurfacePtr grey_surface(const LiveSnapshot& snapshot, LiveImage image) {
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, snapshot.width, snapshot.height), &cairo_surface_destroy);
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  const bool difference = image == LiveImage::difference && snapshot.has_off;
  const int full_scale = std::max(1, difference ? snapshot.maxval / kDifferenceGain : snapshot.maxval);
  for (int y = 0; y < snapshot.height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(y) * stride);
    for (int x = 0; x < snapshot.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(snapshot.width) + static_cast<std::size_t>(x);
      const int value = difference ? std::max(0, snapshot.on[i] - snapshot.off[i]) : snapshot.on[i];
      const auto grey = static_cast<std::uint32_t>(std::min(255, value * 255 / full_scale));
      row[x] = grey << 16 | grey << 8 | grey;
    }
  }
  cairo_surface_mark_dirty(surface.get());
  return surface;
}

Eigen::Isometry3d world_from_base(const PoseEstimate& estimate) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation_from_rpy(estimate.roll, estimate.pitch, estimate.yaw);
  t.translation() = Eigen::Vector3d(estimate.x, estimate.y, estimate.z);
  return t;
}

// Maps camera pixels onto the canvas and world points through the camera.
class Projector {
 public:
  Projector(const LiveViewGeometry& geometry, const PoseEstimate& estimate, double scale)
      : geometry_(geometry), scale_(scale) {
    if (geometry.camera_from_world) {
      camera_from_world_ = to_isometry(*geometry.camera_from_world);
    } else if (estimate.ok) {
      camera_from_world_ = to_isometry(geometry.camera_from_base) * world_from_base(estimate).inverse();
    }
  }

  bool posed() const { return camera_from_world_.has_value(); }
  // Pixel centres are at integer coordinates, cairo's at +0.5.
  Eigen::Vector2d canvas(const Eigen::Vector2d& pixel) const {
    return {(pixel.x() + 0.5) * scale_, (pixel.y() + 0.5) * scale_ + kBannerHeight};
  }
  // The canvas point of a world point seen by the camera; false when it is not in the image.
  bool world(const Eigen::Vector3d& point_w, Eigen::Vector2d& point) const {
    if (!camera_from_world_) return false;
    const Eigen::Vector3d point_c = *camera_from_world_ * point_w;
    Eigen::Vector2d pixel;
    if (point_c.z() <= 0 || !geometry_.camera.project(point_c, pixel) || !geometry_.camera.in_image(pixel)) return false;
    point = canvas(pixel);
    return true;
  }
  // Points along the world segment a-b, each one that projects joined to the last one that did.
  void segment(cairo_t* cr, const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    constexpr int kSteps = 16;  // a straight side bends under a fisheye
    bool drawing = false;
    for (int k = 0; k <= kSteps; ++k) {
      Eigen::Vector2d point;
      if (!world(a + (b - a) * (static_cast<double>(k) / kSteps), point)) {
        drawing = false;
        continue;
      }
      (drawing ? cairo_line_to : cairo_move_to)(cr, point.x(), point.y());
      drawing = true;
    }
  }

 private:
  const LiveViewGeometry& geometry_;
  double scale_;
  std::optional<Eigen::Isometry3d> camera_from_world_;
};

// `prefix` and the number beside `at`: up and right (what a source measured), or down and
// right (the map's, which may stand at the same place).
enum class Side { above, below };
void label(cairo_t* cr, const Eigen::Vector2d& at, const char* prefix, int number, Side side = Side::above) {
  char text[32];
  std::snprintf(text, sizeof text, "%s%d", prefix, number);
  cairo_move_to(cr, at.x() + 6, side == Side::above ? at.y() - 6 : at.y() + 14);
  cairo_show_text(cr, text);
  cairo_new_path(cr);
}

void circle(cairo_t* cr, const Eigen::Vector2d& at, double radius) {
  cairo_new_sub_path(cr);
  cairo_arc(cr, at.x(), at.y(), radius, 0, 2 * kPi);
}

void cross(cairo_t* cr, const Eigen::Vector2d& at, double half) {
  cairo_move_to(cr, at.x() - half, at.y() - half);
  cairo_line_to(cr, at.x() + half, at.y() + half);
  cairo_move_to(cr, at.x() - half, at.y() + half);
  cairo_line_to(cr, at.x() + half, at.y() - half);
}

void draw_map(cairo_t* cr, const Projector& project, const MarkerMap& map) {
  set_colour(cr, kMapColour, 0.8);
  cairo_set_line_width(cr, 1);
  for (const DotMarker& marker : map.dot_markers) {
    const std::array<int, 4> outline = {dot::kCellO, dot::kCellX, dot::cell_index(3, 3), dot::kCellY};
    for (std::size_t k = 0; k < outline.size(); ++k) {
      project.segment(cr, dot::cell_in_world(marker, outline[k]), dot::cell_in_world(marker, outline[(k + 1) % 4]));
    }
    cairo_stroke(cr);
    Eigen::Vector2d origin;
    if (project.world(dot::cell_in_world(marker, dot::kCellO), origin)) label(cr, origin, "map ", marker.id, Side::below);
  }
  for (const SquareMarker& square : map.square_markers) {
    for (std::size_t side = 0; side < 4; ++side) project.segment(cr, square.corners[side], square.corners[(side + 1) % 4]);
    cairo_stroke(cr);
  }
  for (const LedLandmark& led : map.led_landmarks) {
    Eigen::Vector2d at;
    if (!project.world(led.position, at)) continue;
    cairo_move_to(cr, at.x(), at.y() - 6);
    cairo_line_to(cr, at.x() + 6, at.y());
    cairo_line_to(cr, at.x(), at.y() + 6);
    cairo_line_to(cr, at.x() - 6, at.y());
    cairo_close_path(cr);
    cairo_stroke(cr);
  }
}

void draw_box(cairo_t* cr, const Projector& project, const outside_in::BoxBody& body, const PoseEstimate& estimate) {
  const Eigen::Isometry3d t_w_b = world_from_base(estimate);
  std::array<Eigen::Vector3d, 8> corners;
  for (std::size_t k = 0; k < 8; ++k) {
    corners[k] = t_w_b * Eigen::Vector3d((k & 1 ? 0.5 : -0.5) * body.length, (k & 2 ? 0.5 : -0.5) * body.width,
                                         k & 4 ? body.height : 0.0);
  }
  set_colour(cr, kBoxColour);
  cairo_set_line_width(cr, 2);
  for (std::size_t a = 0; a < 8; ++a) {
    for (const std::size_t bit : {1u, 2u, 4u}) {
      if ((a & bit) == 0) project.segment(cr, corners[a], corners[a | bit]);
    }
  }
  cairo_stroke(cr);
}

void draw_observations(cairo_t* cr, const Projector& project, const LiveSourceAttempt& source) {
  const auto& points = source.observations;
  cairo_set_line_width(cr, 1.5);
  switch (source.kind) {
    case SourceKind::dot: {
      set_colour(cr, kDotColour);
      int labelled = -1;
      for (const PointObservation& p : points) {
        const Eigen::Vector2d at = project.canvas(p.pixel);
        circle(cr, at, 5);
        cairo_stroke(cr);
        if (p.landmark != labelled) label(cr, at, "ID ", p.landmark);
        labelled = p.landmark;
      }
      break;
    }
    case SourceKind::square: {
      set_colour(cr, kSquareColour);
      for (std::size_t k = 0; k < points.size(); ++k) {
        const Eigen::Vector2d at = project.canvas(points[k].pixel);
        (k == 0 ? cairo_move_to : cairo_line_to)(cr, at.x(), at.y());
      }
      if (points.size() == 4) cairo_close_path(cr);
      cairo_stroke(cr);
      for (const PointObservation& p : points) {
        const Eigen::Vector2d at = project.canvas(p.pixel);
        circle(cr, at, 4);
        cairo_fill(cr);
        label(cr, at, "c", p.point);
      }
      break;
    }
    case SourceKind::led:
      set_colour(cr, kLedColour);
      for (const PointObservation& p : points) {
        const Eigen::Vector2d at = project.canvas(p.pixel);
        circle(cr, at, 6);
        cairo_stroke(cr);
        label(cr, at, "L", p.landmark);
      }
      break;
    case SourceKind::external:
    case SourceKind::fused:
      break;
  }
  // The measured points' landmarks reprojected from the pose: how well the pose explains them.
  set_colour(cr, kReprojectedColour);
  for (const PointObservation& p : points) {
    Eigen::Vector2d at;
    if (project.world(p.world, at)) cross(cr, at, 3);
  }
  cairo_stroke(cr);
}

std::string banner_pose(const LiveSnapshot& snapshot) {
  const PoseEstimate& e = snapshot.estimate;
  char line[200];
  if (e.ok) {
    std::snprintf(line, sizeof line, "seq %llu  %s  x %.3f y %.3f z %.3f m  yaw %.1f deg  conf %.2f",
                  static_cast<unsigned long long>(e.seq), std::string(to_string(e.source)).c_str(), e.x, e.y, e.z,
                  e.yaw * 180 / kPi, e.confidence);
  } else {
    std::snprintf(line, sizeof line, "seq %llu  no pose", static_cast<unsigned long long>(e.seq));
  }
  return line;
}

std::string banner_outcomes(const LiveSnapshot& snapshot) {
  std::string line;
  if (snapshot.verdict) line.append("strobe ").append(strobe_verdict_name(*snapshot.verdict)).append("   ");
  if (!snapshot.computed) line.append("sources not run (strobe check failed)");
  else if (snapshot.sources.empty()) line.append("no source (the map has no landmarks)");
  for (const LiveSourceAttempt& source : snapshot.sources) {
    line.append(to_string(source.kind)).append(": ").append(source.outcome).append("   ");
  }
  return line;
}

}  // namespace

std::optional<LiveImage> live_image_named(std::string_view name) {
  if (name == "on") return LiveImage::on;
  if (name == "difference") return LiveImage::difference;
  return std::nullopt;
}

LiveViewGeometry live_view_geometry(const Localizer& localizer) {
  const LocalizerSetup& setup = localizer.setup();
  LiveViewGeometry geometry{CameraModel(setup.camera), setup.mount.inverse(), std::nullopt, std::nullopt, setup.map};
  if (setup.outside_in) {
    if (const outside_in::OutsideInSource* source = localizer.find_source<outside_in::OutsideInSource>()) {
      geometry.camera_from_world = source->floor().camera_from_world;
      geometry.body = setup.outside_in->body;
    }
  }
  return geometry;
}

void draw_live_view(const LiveSnapshot& snapshot, const LiveViewGeometry& geometry, LiveImage image, int max_width,
                    BgrxImage& out) {
  const double scale = std::min(1.0, static_cast<double>(std::max(max_width, 64)) / snapshot.width);
  const int width = std::max(1, static_cast<int>(std::lround(snapshot.width * scale)));
  const int height = static_cast<int>(std::lround(snapshot.height * scale)) + kBannerHeight;
  const SurfacePtr frame = grey_surface(snapshot, image);
  const SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height), &cairo_surface_destroy);
  const ContextPtr context(cairo_create(surface.get()), &cairo_destroy);
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_paint(cr);
  cairo_save(cr);
  cairo_translate(cr, 0, kBannerHeight);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, frame.get(), 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
  cairo_paint(cr);
  cairo_restore(cr);

  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 11);
  const Projector project(geometry, snapshot.estimate, scale);
  set_colour(cr, kBlobColour, 0.8);
  cairo_set_line_width(cr, 1);
  for (const LiveBlob& blob : snapshot.blobs) {
    const Eigen::Vector2d a = project.canvas({blob.x_min - 0.5, blob.y_min - 0.5});
    const Eigen::Vector2d b = project.canvas({blob.x_max + 0.5, blob.y_max + 0.5});
    cairo_rectangle(cr, a.x() - 1, a.y() - 1, b.x() - a.x() + 2, b.y() - a.y() + 2);
  }
  cairo_stroke(cr);
  if (project.posed()) draw_map(cr, project, geometry.map);
  for (const LiveSourceAttempt& source : snapshot.sources) draw_observations(cr, project, source);
  if (geometry.body && snapshot.estimate.ok) draw_box(cr, project, *geometry.body, snapshot.estimate);

  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_set_font_size(cr, 11);
  const std::string lines[2] = {banner_pose(snapshot) + (image == LiveImage::difference && snapshot.has_off ? "  (on-off x4)" : ""),
                                banner_outcomes(snapshot)};
  for (int k = 0; k < 2; ++k) {
    cairo_move_to(cr, 6, 15 + 18 * k);
    cairo_show_text(cr, lines[k].c_str());
  }
  cairo_surface_flush(surface.get());

  out.width = width;
  out.height = height;
  out.stride = cairo_image_surface_get_stride(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  out.pixels.assign(data, data + static_cast<std::ptrdiff_t>(out.stride) * height);
}

}  // namespace irloc::firmware
