#pragma once
// Tape pixels of a strobe pair: the LED-on minus LED-off difference, thresholded, then the
// thin-line extractor (binarize, erode, dilate, subtract): lamps, windows and the residue of
// people vanish, tape survives (the paper's steps iv-vii). Bit-packed (algo/kernels/thin_lines.hpp).

#include <cstdint>
#include <span>

#include "algo/core/image_view.hpp"
#include "algo/kernels/bit_image.hpp"
#include "algo/kernels/pixel_run.hpp"
#include "algo/kernels/thin_lines.hpp"

namespace irloc::square {

class TapeMask {
 public:
  // Works on the width x height region of frames whose top-left pixel is (x, y) (the part of the
  // frame that sees the ceiling); sized at start-up for frames of pixel_bits (8: 8-bit frames,
  // more: 16-bit ones). element_radius: more than half the widest tape in pixels.
  TapeMask(int x, int y, int width, int height, int element_radius, int pixel_bits);

  // on, off: the two frames of a pair, containing the region, of the depth set up (wide() says
  // which). Tape is on - off > threshold. Allocates nothing.
  void extract(const GrayImageView& on, const GrayImageView& off, std::uint16_t threshold);
  // The same from the shared pass's foreground runs of the whole frame (pair_pass.hpp), when they
  // are at the tape threshold: no second pass over the pair.
  void extract(std::span<const PixelRun> frame_runs) { thin_lines_.extract(frame_runs, x_, y_); }
  bool wide() const { return wide_; }

  // The tape pixels over the region (mask pixel (0, 0) is frame pixel (x, y)); valid until the
  // next extract().
  const BitImage& mask() const { return thin_lines_.lines(); }
  int x() const { return x_; }
  int y() const { return y_; }

 private:
  int x_, y_, width_, height_;
  bool wide_;  // 16-bit frames
  ThinLineExtractor thin_lines_;
};

}  // namespace irloc::square
