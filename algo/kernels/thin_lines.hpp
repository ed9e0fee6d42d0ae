#pragma once
// The thin-line extractor of the square-marker path: binarize the strobe difference, erode,
// dilate, subtract. An opening (erode then dilate) with a square element wider than the tape
// keeps only large bright areas (lamps, windows); what the binary mask has and the opening lacks
// is thin bright structure: the tape.
//
// On bit-packed rows (bit_image.hpp): the binarization packs the fused front end's flag row (one
// vector pass over the pair per row, flag_row.hpp) into bits; the square element is separable, so
// the opening is a horizontal and a vertical erosion, then a vertical and a horizontal dilation,
// 64 pixels per word operation (a window of 2r+1 pixels by log2(2r+1) shift-and steps). Empty
// rows are skipped, and the vertical passes only touch rows whose whole window is set (erosion)
// or whose window has a set row (dilation): a sparse IR frame costs little more than reading it.
// The mask may also come from runs of the shared frame pass (pair_pass.hpp), which then is the
// only pass over the pair. Element pixels outside the image are ignored (OpenCV's default border
// for cv::erode / cv::dilate): the result equals binarize, cv::erode, cv::dilate, subtract
// exactly.

#include <cstdint>
#include <span>
#include <vector>

#include "algo/core/image_view.hpp"
#include "algo/kernels/bit_image.hpp"
#include "algo/kernels/pixel_run.hpp"

namespace irloc {

// Sized for width x height frames at start-up; extract() allocates nothing.
class ThinLineExtractor {
 public:
  // element_radius r: the square element spans 2r + 1 pixels each way; it must exceed half the
  // widest tape width in pixels to erase the tape. 0 <= r <= kMaxRadius.
  ThinLineExtractor(int width, int height, int element_radius);
  static constexpr int kMaxRadius = 63;

  // lines(x, y) set where on - off > threshold and the opening of that mask is 0. on and off
  // have the extractor's size.
  void extract(ImageView8 on, ImageView8 off, std::uint8_t threshold);
  void extract(ImageView16 on, ImageView16 off, std::uint16_t threshold);
  // The same from a frame pass already made: runs (raster order) of the foreground on - off >
  // threshold of a larger frame whose pixel (x0, y0) is the extractor's (0, 0); runs or their
  // parts outside the extractor's area are left out.
  void extract(std::span<const PixelRun> runs, int x0, int y0);

  const BitImage& lines() const { return lines_; }
  // The intermediate masks of the last extract(), for inspection and tests.
  const BitImage& binary() const { return binary_; }
  const BitImage& opened() const { return opened_; }

 private:
  template <typename Pixel>
  void binarize(ImageView<const Pixel> on, ImageView<const Pixel> off, Pixel threshold);
  void binarize(std::span<const PixelRun> runs, int x0, int y0);
  // The opening (erosion, then dilation, each separable: rows, then columns) of binary_, and
  // lines_ = binary_ without it.
  void open_and_subtract();
  void erode_rows();
  void erode_columns();
  void dilate_columns();
  void dilate_rows_and_subtract();
  // set_rows_before_ of image's rows; set_rows_in(from, to): how many of rows [from, to) are set.
  void count_set_rows(const BitImage& image);
  int set_rows_in(int from, int to) const;

  int radius_;
  std::vector<std::uint16_t> flags_;    // one row of the difference's flags
  std::vector<std::uint64_t> padded_;   // one row and a word of border each side
  std::vector<int> set_rows_before_;    // prefix counts of set rows, for the vertical windows
  BitImage binary_;
  BitImage eroded_rows_;  // eroded along rows
  BitImage eroded_;       // and along columns: the erosion
  BitImage dilated_columns_;
  BitImage opened_;
  BitImage lines_;
};

}  // namespace irloc
