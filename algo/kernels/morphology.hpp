#pragma once
// Grey-level (and so binary) erosion and dilation with square or cross structuring elements.
//
// erode: out(x, y) = min of in over the element centred at (x, y); dilate: the max. Pixels of the
// element that fall outside the image are ignored, which is OpenCV's default border for
// cv::erode / cv::dilate (BORDER_CONSTANT with morphologyDefaultBorderValue()). On a 0/255 mask
// this is binary erosion/dilation.

#include <cstdint>
#include <vector>

#include "algo/core/image_view.hpp"

namespace irloc {

enum class ElementShape {
  square,  // every pixel of the (2r+1) x (2r+1) box
  cross,   // the centre row and column of the box (cv::MORPH_CROSS)
};

struct StructuringElement {
  ElementShape shape = ElementShape::square;
  int radius = 1;  // half-size r >= 0: the element spans 2r+1 pixels each way
};

// Holds one row of scratch sized at start-up for images up to max_width pixels wide.
// in and out have the same size and must not overlap. Cost per pixel: about 2(2r+1) vector
// min/max operations / 16 lanes.
class Morphology {
 public:
  explicit Morphology(int max_width);

  void erode(ImageView8 in, StructuringElement element, MutableImageView8 out);
  void dilate(ImageView8 in, StructuringElement element, MutableImageView8 out);

 private:
  template <bool kErode>
  void filter(ImageView8 in, StructuringElement element, MutableImageView8 out);

  std::vector<std::uint8_t> column_extreme_;  // per column: min/max over the element's rows
};

}  // namespace irloc
