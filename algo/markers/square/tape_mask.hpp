#pragma once
// Tape pixels of a strobe pair: the LED-on minus LED-off difference, thresholded, then the
// thin-line extractor (binarize, erode, dilate, subtract): lamps, windows and the residue of
// people vanish, tape survives (the paper's steps iv-vii).

#include <array>
#include <cstdint>
#include <variant>

#include "algo/core/image.hpp"
#include "algo/core/image_view.hpp"
#include "algo/kernels/thin_lines.hpp"

namespace irloc {

class TapeMask {
 public:
  // Works on the width x height region of frames whose top-left pixel is (x, y) (the part of the
  // frame that sees the ceiling); sized at start-up. element_radius: more than half the widest
  // tape in pixels. threshold: 0 = automatic per frame (histogram of the difference).
  TapeMask(int x, int y, int width, int height, int element_radius, std::uint16_t threshold);

  // on, off: the two frames of a pair, containing the region, of one depth. Returns the
  // threshold used. Allocates nothing.
  std::uint16_t extract(const GrayImageView& on, const GrayImageView& off);

  // 255 on tape pixels, 0 elsewhere, over the region (mask pixel (0, 0) is frame pixel (x, y));
  // valid until the next extract().
  ImageView8 mask() const { return mask_.view(); }
  int x() const { return x_; }
  int y() const { return y_; }

 private:
  template <typename Pixel>
  std::uint16_t extract_depth(ImageView<const Pixel> on, ImageView<const Pixel> off);

  int x_, y_;
  std::uint16_t fixed_threshold_;
  ThinLineExtractor thin_lines_;
  Image8 difference8_;
  Image16 difference16_;
  Image8 mask_;
  std::array<std::uint32_t, 4096> histogram_{};
};

}  // namespace irloc
