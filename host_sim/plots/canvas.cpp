#include "host_sim/plots/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>

#include "host_sim/plots/png_file.hpp"

namespace irloc::sim::drawing {

Colour camera_colour(std::size_t camera) {
  constexpr Colour kCameraColours[] = {{0.12, 0.47, 0.71}, {0.89, 0.10, 0.11}, {0.20, 0.63, 0.17}, {0.60, 0.31, 0.64},
                                       {1.00, 0.50, 0.00}, {0.65, 0.34, 0.16}, {0.97, 0.51, 0.75}, {0.40, 0.40, 0.40}};
  return kCameraColours[camera % std::size(kCameraColours)];
}

Colour lighter(Colour c, double amount) { return {c.r + amount * (1 - c.r), c.g + amount * (1 - c.g), c.b + amount * (1 - c.b)}; }

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

Canvas::Canvas(int width, int height)
    : surface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height)), cr_(cairo_create(surface_)) {
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
  cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, 13);
}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(surface_);
}

void Canvas::save(const std::filesystem::path& png) const { write_png(png, surface_); }

void set_colour(cairo_t* cr, Colour c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void text(cairo_t* cr, double x, double y, const std::string& label, double align) {
  cairo_text_extents_t extents;
  cairo_text_extents(cr, label.c_str(), &extents);
  cairo_move_to(cr, x - align * extents.width, y);
  cairo_show_text(cr, label.c_str());
  cairo_new_path(cr);  // show_text leaves a current point: the next shape must not start from it
}

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

Axes TopViewExtent::equal_axes(double left, double top, double size, double margin_fraction, double margin_m) const {
  double x0 = x0_, x1 = x1_, y0 = y0_, y1 = y1_;
  if (x0 > x1) { x0 = y0 = -1; x1 = y1 = 1; }
  const double margin = margin_fraction * std::max({x1 - x0, y1 - y0, 0.5}) + margin_m;
  x0 -= margin; x1 += margin; y0 -= margin; y1 += margin;
  const double scale = size / std::max(x1 - x0, y1 - y0);
  return Axes{left, top, (x1 - x0) * scale, (y1 - y0) * scale, x0, x1, y0, y1};
}

void Axes::draw(cairo_t* cr, const std::string& x_label, const std::string& y_label, const std::string& title,
                bool grid) const {
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
  cairo_rotate(cr, -std::numbers::pi / 2);
  text(cr, 0, 0, y_label, 0.5);
  cairo_restore(cr);
  cairo_set_font_size(cr, 14);
  text(cr, left + width / 2, top - 10, title, 0.5);
  cairo_set_font_size(cr, 13);
}

}  // namespace irloc::sim::drawing
