#pragma once
// What every picture of plots.hpp draws with (cairo): the canvas, colours, text, axes with ticks,
// legends and the colour scale of heat maps.

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <cairo.h>

namespace irloc::sim::drawing {

struct Colour {
  double r, g, b;
};
inline constexpr Colour kTruth{0.10, 0.35, 0.80};
inline constexpr Colour kEstimate{0.85, 0.20, 0.10};
inline constexpr Colour kGross{0.95, 0.65, 0.0};
inline constexpr Colour kGrey{0.55, 0.55, 0.55};
// One colour per wall camera (outside-in hand-over), cycled beyond eight.
Colour camera_colour(std::size_t camera);
// c moved `amount` (0..1) of the way to white.
Colour lighter(Colour c, double amount);
// Perceptual-ish colour scale from dark blue through green to yellow, t in [0, 1].
Colour colour_scale(double t);

// Owns a cairo image surface and context, white; writes the PNG on save().
class Canvas {
 public:
  Canvas(int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  void save(const std::filesystem::path& png) const;

 private:
  cairo_surface_t* surface_;
  cairo_t* cr_;
};

void set_colour(cairo_t* cr, Colour c);
// `label` with its baseline at y, starting at x (align 0), centred on it (0.5) or ending there (1).
void text(cairo_t* cr, double x, double y, const std::string& label, double align = 0);
// A tick spacing of 1, 2 or 5 x 10^n giving about `count` ticks over `span`.
double nice_step(double span, int count);
std::string tick_label(double value, double step);
// A column of colour boxes with their labels, the first at (x, y).
void legend(cairo_t* cr, double x, double y, const std::vector<std::pair<Colour, std::string>>& entries);

// A plot area mapping data (x, y) to canvas pixels, with axes, ticks and labels.
struct Axes {
  double left, top, width, height;  // canvas pixels
  double x0, x1, y0, y1;            // data range

  double px(double x) const { return left + (x - x0) / (x1 - x0) * width; }
  double py(double y) const { return top + height - (y - y0) / (y1 - y0) * height; }

  // Grid lines are left out over images (heat maps).
  void draw(cairo_t* cr, const std::string& x_label, const std::string& y_label, const std::string& title,
            bool grid = true) const;
};

// What a top view of the room shows (m), gathered point by point; then its axes, with equal
// scales on x and y.
class TopViewExtent {
 public:
  void add(double x, double y) {
    x0_ = std::min(x0_, x), x1_ = std::max(x1_, x);
    y0_ = std::min(y0_, y), y1_ = std::max(y1_, y);
  }
  // Axes at (left, top) whose longer side is `size` canvas pixels. The extent is widened on every
  // side by `margin_fraction` of its longer span (at least 0.5 m) plus `margin_m`; with no point
  // it is -1..1 m.
  Axes equal_axes(double left, double top, double size, double margin_fraction, double margin_m = 0) const;

 private:
  double x0_ = 1e300, x1_ = -1e300, y0_ = 1e300, y1_ = -1e300;
};

}  // namespace irloc::sim::drawing
