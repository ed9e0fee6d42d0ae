#pragma once
// Stage 6: how far a dot pose can be trusted, in [0, 1] (docs/dot_markers.md):
//
//   marker evidence  e_k = grey_k * min(1, margin_k / full_margin)       (0 when margin_k <= 0)
//   markers combined E   = 1 - prod_k (1 - e_k)       (independent markers: any good one suffices)
//   geometry         G   = exp(-rms^2 / (2 rms_scale^2))    (rms: reprojection RMS of every dot, px)
//   confidence           = E * G
//
// grey_k is the geometric mean of the grey-level posteriors (grey_level_model.hpp) of marker k's
// dots; margin_k its per-cell contrast margin (cell_contrast.hpp).

#include <span>

#include "algo/markers/dot/dot_source_config.hpp"

namespace irloc::dot {

struct MarkerEvidence {
  double grey = 0;    // in [0, 1]
  double margin = 0;  // in [-1, 1]
};

double pose_confidence(const DotSourceConfig& config, std::span<const MarkerEvidence> markers, double rms_px);

}  // namespace irloc::dot
