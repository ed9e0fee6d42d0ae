#pragma once
// Erosion or dilation of a binary mask (every pixel 0 or 255) by the (2r+1) x (2r+1) square, a row
// at a time, at a cost per pixel that does not grow with r:
//  - vertically, per column, the count of the window's rows whose pixel is set (dilation) or clear
//    (erosion), kept by adding the row that enters the window and subtracting the one that leaves;
//  - horizontally, the max (min) of the counts' row over the window by doubling: a step with
//    shift s takes the max of x - s, x and x + s, which turns a window of radius a into one of
//    a + s when s <= 2a + 1, so radius r takes about log3(2r + 1) steps (12: shifts 1, 3, 8).
// Pixels outside the image are ignored, as in Morphology (morphology.hpp), which it equals on
// 0/255 masks (kernels_test). Vector loops of 16 or 32 bytes (wide_vectors.hpp).

#include <cstdint>
#include <vector>

#include "algo/core/image_view.hpp"

namespace irloc {

class SquareMaskFilter {
 public:
  enum class Operation { erode, dilate };
  static constexpr int kMaxRadius = 127;  // the window's count fits a byte

  // Allocates its scratch here, for images up to max_width wide; radius 0..kMaxRadius
  // (std::invalid_argument otherwise).
  SquareMaskFilter(int max_width, int radius, Operation operation);

  int radius() const { return radius_; }

  // Row y of the filtered image. Rows are asked in turn, y = 0, 1, ..., in.height() - 1 (y = 0
  // starts a new image). When row y is asked, the rows of `in` up to min(y + radius, height - 1)
  // hold their final values and row y - radius - 1 is unchanged since row y - 1 was asked. The
  // pointer is valid until the next call.
  const std::uint8_t* row(ImageView8 in, int y);
  // Takes row y's turn in that sequence without forming it (only its window's counts are kept):
  // for a caller that does not need row y, at a small part of its cost.
  void skip_row(ImageView8 in, int y);

  // The whole image: out = filter(in); in and out have the same size and do not overlap.
  void apply(ImageView8 in, MutableImageView8 out);

 private:
  // The indicator of a counted pixel is the pixel xor this: set ones count for dilation, clear
  // ones (flipped) for erosion.
  std::uint8_t counted_flip() const { return operation_ == Operation::erode ? 255 : 0; }
  // Brings the per-column counts to row y's window.
  void count_window(ImageView8 in, int y);
  void filter_row(ImageView8 in, int y, std::uint8_t* out);

  int max_width_;
  int radius_;
  Operation operation_;
  std::uint8_t neutral_;           // the padding: 0 for dilation, 255 for erosion
  int rows_counted_ = 0;           // rows of the current image added to counts_
  std::vector<std::uint8_t> counts_;  // per column: set (dilation) / clear (erosion) pixels in the window
  std::vector<std::uint8_t> padded_[2];  // radius_ neutral bytes, a row, radius_ neutral bytes
  std::vector<std::uint8_t> result_;  // row()'s result
};

}  // namespace irloc
