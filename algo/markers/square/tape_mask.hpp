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
  // Sized for width x height frames at start-up. element_radius: more than half the widest tape
  // in pixels. threshold: 0 = automatic per frame (histogram of the difference).
  TapeMask(int width, int height, int element_radius, std::uint16_t threshold);

  // on, off: the two frames of a pair, of the configured size and of one depth. Returns the
  // threshold used. Allocates nothing.
  std::uint16_t extract(const GrayImageView& on, const GrayImageView& off);

  // 255 on tape pixels, 0 elsewhere; valid until the next extract().
  ImageView8 mask() const { return mask_.view(); }

 private:
  template <typename Pixel>
  std::uint16_t extract_depth(ImageView<const Pixel> on, ImageView<const Pixel> off);

  std::uint16_t fixed_threshold_;
  ThinLineExtractor thin_lines_;
  Image8 difference8_;
  Image16 difference16_;
  Image8 mask_;
  std::array<std::uint32_t, 4096> histogram_{};
};

}  // namespace irloc
