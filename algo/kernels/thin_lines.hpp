#pragma once
// The thin-line extractor of the square-marker path: binarize, erode, dilate, subtract. An opening
// (erode then dilate) with an element wider than the tape keeps only large bright areas (lamps,
// windows); what the binary mask has and the opening lacks is thin bright structure: the tape.

#include <cstdint>

#include "algo/core/image.hpp"
#include "algo/core/image_view.hpp"
#include "algo/kernels/morphology.hpp"

namespace irloc {

// Sized for width x height frames at start-up; extract() allocates nothing.
class ThinLineExtractor {
 public:
  // element: its radius must exceed half the widest tape width in pixels to erase the tape.
  ThinLineExtractor(int width, int height, StructuringElement element);

  // lines(x, y) = 255 where image > threshold and the opening of that mask is 0, else 0.
  // image and lines have the extractor's size.
  void extract(ImageView8 image, std::uint8_t threshold, MutableImageView8 lines);
  void extract(ImageView16 image, std::uint16_t threshold, MutableImageView8 lines);

  // The intermediate masks of the last extract(), for inspection and tests.
  ImageView8 binary() const { return binary_.view(); }
  ImageView8 opened() const { return opened_.view(); }

 private:
  void open_and_subtract(MutableImageView8 lines);

  StructuringElement element_;
  Morphology morphology_;
  Image8 binary_;
  Image8 eroded_;
  Image8 opened_;
};

}  // namespace irloc
