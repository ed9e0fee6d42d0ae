#include "algo/markers/led/led_detector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
                         LedDetectionCounters& counters) {
  detections.clear();
  counters = {};
  std::visit(
      [&](const auto& on_view) {
        using View = std::decay_t<decltype(on_view)>;
        const View* off_view = off != nullptr ? std::get_if<View>(off) : nullptr;
        detect_in(on_view, off_view, detections, counters);
      },
      on);
  std::sort(detections.begin(), detections.end(),
            [](const LedDetection& a, const LedDetection& b) { return a.flux > b.flux; });
}

template <typename Pixel>
void LedDetector::detect_in(ImageView<const Pixel> on, const ImageView<const Pixel>* off,
                            LedDetectionList& detections, LedDetectionCounters& counters) {
  const MutableImageView8 mask(mask_.data(), width_, height_);
  threshold_binary(on, static_cast<Pixel>(threshold_), 255, mask);
  counters.blobs = labeller_.label(mask, on, BlobParams{1}, blobs_);

  for (const Blob& blob : blobs_) {
    if (blob.area > static_cast<std::uint32_t>(config_.max_area)) {
      ++counters.too_large;
      continue;
    }
    if (blob.area >= 5 && blob.elongation() > config_.max_elongation) {
      ++counters.elongated;
      continue;
    }
    if (off != nullptr) {
      // Always-on: the LED-off frame is bright within off_search_px of the spot.
      const int x0 = std::max(0, blob.x_min - config_.off_search_px);
      const int x1 = std::min(width_ - 1, blob.x_max + config_.off_search_px);
      const int y0 = std::max(0, blob.y_min - config_.off_search_px);
      const int y1 = std::min(height_ - 1, blob.y_max + config_.off_search_px);
      std::uint32_t off_peak = 0;
      for (int y = y0; y <= y1; ++y) {
        const Pixel* row = off->row(y);
        for (int x = x0; x <= x1; ++x) off_peak = std::max<std::uint32_t>(off_peak, row[x]);
      }
      if (off_peak <= off_threshold_) {
        ++counters.dark_when_off;
        continue;
      }
    }
    // Centroid window: the spot's box and a margin of background around it.
    const int m = std::max(1, config_.centroid_margin);  // the ring needs a window of 3 x 3 or more
    const int x0 = blob.x_min - m, x1 = blob.x_max + m, y0 = blob.y_min - m, y1 = blob.y_max + m;
    if (x0 < 0 || y0 < 0 || x1 >= width_ || y1 >= height_) {
      ++counters.at_border;
      continue;
    }
    // Background: the mean of the window's outermost ring, which must hold no other spot.
    double ring_sum = 0;
    int ring_count = 0;
    bool crowded = false;
    for (int y = y0; y <= y1; ++y) {
      const Pixel* row = on.row(y);
      const bool edge_row = y == y0 || y == y1;
      for (int x = x0; x <= x1; x += (edge_row || x == x1) ? 1 : x1 - x0) {
        crowded |= row[x] > threshold_;
        ring_sum += row[x];
        ++ring_count;
      }
    }
    if (crowded) {
      ++counters.crowded;
      continue;
    }
    const double background = ring_sum / ring_count;
    double sum = 0, sum_x = 0, sum_y = 0;
    for (int y = y0 + 1; y < y1; ++y) {
      const Pixel* row = on.row(y);
      for (int x = x0 + 1; x < x1; ++x) {
        const double weight = std::max(0.0, row[x] - background);
        sum += weight;
        sum_x += weight * x;
        sum_y += weight * y;
      }
    }
    if (sum <= 0) continue;
    const bool saturated = blob.peak >= (1u << pixel_bits_) - 1u;
    const double brightness =
        saturated ? std::numeric_limits<double>::infinity() : static_cast<double>(blob.peak) / threshold_;
    if (!detections.push_back({Eigen::Vector2d(sum_x / sum, sum_y / sum), sum, static_cast<int>(blob.area), brightness})) {
      ++counters.dropped;
    }
  }
}

template void LedDetector::detect_in(ImageView8, const ImageView8*, LedDetectionList&, LedDetectionCounters&);
template void LedDetector::detect_in(ImageView16, const ImageView16*, LedDetectionList&, LedDetectionCounters&);

}  // namespace irloc::led
