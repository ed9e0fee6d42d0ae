#pragma once
// Stage 4b: the per-cell intensity test. Every cell centre of a decoded marker is projected back
// into the image and the strobe difference is averaged there; a populated cell must be about as
// bright as the direction dots and an empty one dark. The margin of the least clear cell says how
// far the decoding is from flipping a bit, whatever the blob threshold did.

#include <array>

#include <Eigen/Core>

#include "algo/core/image_view.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/markers/dot/cell_decoder.hpp"
#include "algo/markers/dot/nominal_plane.hpp"

namespace irloc::dot {

struct CellContrast {
  // min over cells of 2 (level / reference - 1/2) for populated, 2 (1/2 - level / reference) for
  // empty cells, in [-1, 1]: 1 = textbook, 0 = a coin flip, < 0 = a cell contradicts the decoding.
  double margin = -1;
  double reference_level = 0;  // mean difference at O, X and Y, grey levels
};

// window_radius: half-size in pixels of the square averaged at each cell centre.
CellContrast measure_cell_contrast(const DecodedCells& decoded, const NominalPlane& plane, const CameraModel& camera,
                                   const GrayImageView& on, const GrayImageView& off, int window_radius);

// The same test at given pixels (a marker identified by the track, track_identification.hpp): the
// cells in `predicted` whose window lies in the image are read, the reference level is the mean of
// the populated ones among them (at least three; else no verdict, margin -1), and every cell read
// must agree with `populated`.
CellContrast measure_cell_contrast_at(const std::array<Eigen::Vector2d, kCellCount>& pixels, CellMask populated,
                                      CellMask predicted, const GrayImageView& on, const GrayImageView& off,
                                      int window_radius);

}  // namespace irloc::dot
