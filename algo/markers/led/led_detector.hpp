#pragma once
// Finds the active LED landmarks in a strobe pair: spots above a threshold in the LED-on frame
// (one pass of threshold_binary and the BlobLabeller), kept when they are small and round and the
// LED-off frame is bright near them too; then a sub-pixel centre from a background-subtracted,
// intensity-weighted centroid over a window around the spot. Lamps and sunlit patches are larger
// or elongated (their boxes are kept as glare, where an LED may hide); retro-reflectors are dark
// in the LED-off frame; a spot whose window touches other bright pixels (a lamp beside an LED) is
// dropped rather than measured with a biased centre.
// 8- and 16-bit frames; buffers sized at construction, detect() allocates nothing.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "algo/core/image_view.hpp"
#include "algo/core/static_vector.hpp"
#include "algo/kernels/blob_labeller.hpp"
#include "algo/markers/led/led_config.hpp"

namespace irloc::led {

struct LedDetection {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // sub-pixel centre, px
  double flux = 0;                                  // background-subtracted sum of the window, grey levels
  int area = 0;                                     // pixels above the threshold
  // Peak over the detection threshold (>= 1): how far above what is needed to be seen the spot
  // is; an LED of the same kind r times as far is about r^2 times dimmer. Infinite when the peak
  // is saturated (its light is not measured, so it never makes another LED too dim to see).
  double brightness = 1;
};

inline constexpr std::size_t kMaxLedDetections = 32;
using LedDetectionList = StaticVector<LedDetection, kMaxLedDetections>;

// Glare: the boxes (pixels, inclusive) of the bright spots refused for their size or shape (a
// window, a lamp): an LED whose image falls in one merges with it and is not detected, so it is
// not missing there. Beyond the capacity a box is dropped (LedGlareList::dropped()): an LED in it
// then counts as missing, which can cost a pose and never gives a wrong one.
inline constexpr std::size_t kMaxLedGlare = 16;
using LedGlareList = StaticVector<Eigen::AlignedBox2d, kMaxLedGlare>;

// Why spots were not taken as LEDs, per frame.
struct LedDetectionCounters {
  BlobCounters blobs;
  std::uint32_t too_large = 0;
  std::uint32_t elongated = 0;
  std::uint32_t dark_when_off = 0;
  std::uint32_t crowded = 0;       // other bright pixels in the centroid window
  std::uint32_t at_border = 0;     // centroid window leaves the image
  std::uint32_t dropped = 0;       // detections beyond kMaxLedDetections
};

class LedDetector {
 public:
  // pixel_bits: significant bits of the frames (SourceSetup::pixel_bits); thresholds are
  // fractions of that full scale.
  LedDetector(int width, int height, int pixel_bits, const LedSourceConfig& config);

  // off may be empty (no strobe partner): then brightness in the LED-off frame is not tested.
  // Detections come sorted by flux, brightest first; glare: the boxes of the spots refused as too
  // large or elongated.
  void detect(const GrayImageView& on, const GrayImageView* off, LedDetectionList& detections, LedGlareList& glare,
              LedDetectionCounters& counters);

 private:
  template <typename Pixel>
  void detect_in(ImageView<const Pixel> on, const ImageView<const Pixel>* off, LedDetectionList& detections,
                 LedGlareList& glare, LedDetectionCounters& counters);

  LedSourceConfig config_;
  int width_, height_;
  int pixel_bits_;
  std::uint32_t threshold_, off_threshold_;
  std::vector<std::uint8_t> mask_;
  BlobLabeller labeller_;
  BlobList blobs_;
};

}  // namespace irloc::led
