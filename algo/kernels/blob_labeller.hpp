#pragma once
// Connected components of a binary mask (any nonzero pixel is foreground), 8-connectivity,
// straight to per-blob statistics: the separate-kernel path (threshold, morphology, then label).

#include <cstddef>
#include <cstdint>

#include "algo/core/image_view.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/kernels/run_labeller.hpp"

namespace irloc {

class BlobLabeller {
 public:
  // Allocates the run table (max_runs entries) here, at start-up; label() allocates nothing.
  explicit BlobLabeller(std::size_t max_runs);

  // The intensity I of a pixel is the mask value itself (so centroids are geometric for a 0/255 mask)...
  BlobCounters label(ImageView8 mask, BlobParams params, BlobList& blobs);
  // ... or max(intensity(x, y), 1) from an image of the mask's size, e.g. the strobe difference.
  BlobCounters label(ImageView8 mask, ImageView8 intensity, BlobParams params, BlobList& blobs);
  BlobCounters label(ImageView8 mask, ImageView16 intensity, BlobParams params, BlobList& blobs);

  // Labels of the last label() (see RunLabeller::paint_labels).
  void paint_labels(ImageView<std::int32_t> labels) const { runs_.paint_labels(labels); }

 private:
  // row_intensity(y) gives the accessor of row y's intensities I (x -> I >= 1 for a mask pixel).
  template <typename RowIntensity>
  BlobCounters label_with(ImageView8 mask, const RowIntensity& row_intensity, BlobParams params, BlobList& blobs);
  template <typename Pixel>
  BlobCounters label_image(ImageView8 mask, ImageView<const Pixel> intensity, BlobParams params, BlobList& blobs);

  RunLabeller runs_;
};

}  // namespace irloc
