#pragma once
// The dot path's per-frame front end: strobe difference, threshold, run extraction and labelling
// in one pass over the frame pair, straight to per-blob statistics.
//
//   FusedFrontEnd front_end({.width = 1280, .height = 1024});   // start-up: the only allocation
//   BlobList blobs;                                              // kMaxBlobs, in place
//   BlobCounters c = front_end.process(on, off, threshold, blobs);
//   // or, counting the strobe check's evidence in the same pass (strobe_check.hpp):
//   c = front_end.process(on, off, threshold, noise_level, blobs, strobe_counts);
//
// Foreground is on - off > threshold; a blob's intensity I is on - off (>= threshold + 1). Each row
// costs one vector pass (load, min, add, min, subtract, store a flag row); a row with no flag set
// ends there, and the flags of the others are scanned 64 pixels at a time, so a sparse IR frame
// pair costs little more than reading it. Each run's intensity sums are formed from its flags
// (I - threshold) while the row is in the first-level cache and added to its blob's at once: the
// blob statistics never read the frames, or the runs' pixels, again.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/kernels/run_labeller.hpp"
#include "algo/kernels/strobe_check.hpp"

namespace irloc {

struct FrontEndConfig {
  int width = 0;   // frame size, px
  int height = 0;
  std::size_t max_runs = std::size_t{1} << 16;  // foreground runs per frame kept (memory: 116 B each)
  std::uint32_t min_area = 1;                    // smaller blobs are counted, not reported
  int value_bits = 8;  // significant bits of a pixel: 8 for 8-bit frames, 10/12/16 for 16-bit ones
};

class FusedFrontEnd {
 public:
  // Throws std::invalid_argument (at start-up) for a size or depth whose exact blob sums could
  // overflow 64 bits (see blob.hpp).
  explicit FusedFrontEnd(const FrontEndConfig& config);

  // on and off: the LED-on and LED-off frames of one strobe pair, both of the configured size.
  // blobs: cleared, then filled in raster order of each blob's first pixel; blobs.dropped() ==
  // counters.blobs_dropped. Allocates nothing.
  BlobCounters process(ImageView8 on, ImageView8 off, std::uint8_t threshold, BlobList& blobs);
  BlobCounters process(ImageView16 on, ImageView16 off, std::uint16_t threshold, BlobList& blobs);
  // The same, and adds to strobe the pixels with on - off > noise_level and off - on >
  // noise_level, counted in the same vector pass (strobe is not cleared).
  BlobCounters process(ImageView8 on, ImageView8 off, std::uint8_t threshold, std::uint8_t noise_level, BlobList& blobs,
                       StrobeCounts& strobe);
  BlobCounters process(ImageView16 on, ImageView16 off, std::uint16_t threshold, std::uint16_t noise_level,
                       BlobList& blobs, StrobeCounts& strobe);

  // The foreground runs of the last process(), raster order; complete unless its counters report
  // runs_dropped.
  std::span<const PixelRun> runs() const { return runs_.runs(); }
  // Labels of the last process() (see RunLabeller::paint_labels).
  void paint_labels(ImageView<std::int32_t> labels) const { runs_.paint_labels(labels); }
  const FrontEndConfig& config() const { return config_; }

 private:
  template <typename Pixel>
  BlobCounters run(ImageView<const Pixel> on, ImageView<const Pixel> off, Pixel threshold, Pixel noise_level,
                   BlobList& blobs, StrobeCounts* strobe);

  // The flag row as Pixel: 8-bit frames use the first half.
  template <typename Pixel>
  Pixel* flag_row() {
    return reinterpret_cast<Pixel*>(flags_.data());
  }

  FrontEndConfig config_;
  RunLabeller runs_;
  // One row of flags max(on - off - threshold, 0): nonzero exactly at foreground; and of its full
  // 64-pixel blocks as bits.
  std::vector<std::uint16_t> flags_;
  std::vector<std::uint64_t> flag_bits_;
};

}  // namespace irloc
