#include "algo/markers/led/led_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <variant>

#include "algo/kernels/threshold.hpp"

namespace irloc::led {
namespace {

std::uint32_t grey_levels(double fraction, int pixel_bits) {
  const double full_scale = static_cast<double>((1u << pixel_bits) - 1u);
  return static_cast<std::uint32_t>(std::clamp(std::lround(fraction * full_scale), 1L, static_cast<long>(full_scale)));
}

// Runs of a 640 x 480 frame: a bright frame of small spots needs far fewer than one per pixel row
// segment; the table is sized for a frame full of noise-split runs at a tenth of its pixels.
std::size_t run_capacity(int width, int height) { return static_cast<std::size_t>(width) * height / 10 + 1024; }

struct Window {  // pixels [x0, x1] x [y0, y1]
  int x0, y0, x1, y1;
};

// Whether a pixel of the window is above threshold; it stops at the first.
template <typename Pixel>
bool any_above(ImageView<const Pixel> frame, const Window& window, std::uint32_t threshold) {
  for (int y = window.y0; y <= window.y1; ++y) {
    const Pixel* row = frame.row(y);
    for (int x = window.x0; x <= window.x1; ++x) {
      if (row[x] > threshold) return true;
    }
  }
  return false;
}

// The mean of the window's outermost ring; empty when a ring pixel is above threshold (another
// spot crowds this one).
template <typename Pixel>
std::optional<double> ring_background(ImageView<const Pixel> on, const Window& window, std::uint32_t threshold) {
  double ring_sum = 0;
  int ring_count = 0;
  bool crowded = false;
  const auto [x0, y0, x1, y1] = window;
  for (int y = y0; y <= y1; ++y) {
    const Pixel* row = on.row(y);
    const bool edge_row = y == y0 || y == y1;
    for (int x = x0; x <= x1; x += (edge_row || x == x1) ? 1 : x1 - x0) {
      crowded |= row[x] > threshold;
      ring_sum += row[x];
      ++ring_count;
    }
  }
  if (crowded) return std::nullopt;
  return ring_sum / ring_count;
}

// The intensity centroid above the background inside the ring; flux: its sum.
template <typename Pixel>
Eigen::Vector2d centroid(ImageView<const Pixel> on, const Window& window, double background, double& flux) {
  double sum = 0, sum_x = 0, sum_y = 0;
  for (int y = window.y0 + 1; y < window.y1; ++y) {
    const Pixel* row = on.row(y);
    for (int x = window.x0 + 1; x < window.x1; ++x) {
      const double weight = std::max(0.0, row[x] - background);
      sum += weight;
      sum_x += weight * x;
      sum_y += weight * y;
    }
  }
  flux = sum;
  return sum > 0 ? Eigen::Vector2d(sum_x / sum, sum_y / sum) : Eigen::Vector2d::Zero();
}

}  // namespace

LedDetector::LedDetector(int width, int height, int pixel_bits, const LedSourceConfig& config)
    : config_(config),
      width_(width),
      height_(height),
      pixel_bits_(pixel_bits),
      threshold_(grey_levels(config.threshold, pixel_bits)),
      off_threshold_(grey_levels(config.off_threshold, pixel_bits)),
      mask_(static_cast<std::size_t>(width) * height),
      labeller_(run_capacity(width, height)) {}

void LedDetector::detect(const GrayImageView& on, const GrayImageView* off, LedDetectionList& detections,
                         LedGlareList& glare, LedDetectionCounters& counters) {
  detections.clear();
  glare.clear();
  counters = {};
  std::visit(
      [&](const auto& on_view) {
        using View = std::decay_t<decltype(on_view)>;
        const View* off_view = off != nullptr ? std::get_if<View>(off) : nullptr;
        detect_in(on_view, off_view, detections, glare, counters);
      },
      on);
  std::sort(detections.begin(), detections.end(),
            [](const LedDetection& a, const LedDetection& b) { return a.flux > b.flux; });
}

template <typename Pixel>
void LedDetector::detect_in(ImageView<const Pixel> on, const ImageView<const Pixel>* off,
                            LedDetectionList& detections, LedGlareList& glare, LedDetectionCounters& counters) {
  const MutableImageView8 mask(mask_.data(), width_, height_);
  threshold_binary(on, static_cast<Pixel>(threshold_), 255, mask);
  counters.blobs = labeller_.label(mask, on, BlobParams{1}, blobs_);

  for (const Blob& blob : blobs_) {
    const bool too_large = blob.area > static_cast<std::uint32_t>(config_.max_area);
    const bool elongated = !too_large && blob.area >= 5 && blob.elongation() > config_.max_elongation;
    if (too_large || elongated) {
      ++(too_large ? counters.too_large : counters.elongated);
      glare.push_back(
          Eigen::AlignedBox2d(Eigen::Vector2d(blob.x_min, blob.y_min), Eigen::Vector2d(blob.x_max, blob.y_max)));
      continue;
    }
    if (off != nullptr) {
      // Always-on: the LED-off frame is bright within off_search_px of the spot.
      const int reach = config_.off_search_px;
      const Window around{std::max(0, blob.x_min - reach), std::max(0, blob.y_min - reach),
                          std::min(width_ - 1, blob.x_max + reach), std::min(height_ - 1, blob.y_max + reach)};
      if (!any_above(*off, around, off_threshold_)) {
        ++counters.dark_when_off;
        continue;
      }
    }
    // Centroid window: the spot's box and a margin of background around it.
    const int m = std::max(1, config_.centroid_margin);  // the ring needs a window of 3 x 3 or more
    const Window window{blob.x_min - m, blob.y_min - m, blob.x_max + m, blob.y_max + m};
    if (window.x0 < 0 || window.y0 < 0 || window.x1 >= width_ || window.y1 >= height_) {
      ++counters.at_border;
      continue;
    }
    const std::optional<double> background = ring_background(on, window, threshold_);
    if (!background) {
      ++counters.crowded;
      continue;
    }
    double flux = 0;
    const Eigen::Vector2d pixel = centroid(on, window, *background, flux);
    if (flux <= 0) continue;
    const bool saturated = blob.peak >= (1u << pixel_bits_) - 1u;
    const double brightness =
        saturated ? std::numeric_limits<double>::infinity() : static_cast<double>(blob.peak) / threshold_;
    if (!detections.push_back({pixel, flux, static_cast<int>(blob.area), brightness})) ++counters.dropped;
  }
}

template void LedDetector::detect_in(ImageView8, const ImageView8*, LedDetectionList&, LedGlareList&,
                                     LedDetectionCounters&);
template void LedDetector::detect_in(ImageView16, const ImageView16*, LedDetectionList&, LedGlareList&,
                                     LedDetectionCounters&);

}  // namespace irloc::led
