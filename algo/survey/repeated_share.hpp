#pragma once
// The share of a dot's centroid error that the next sighting of its marker repeats (docs/survey.md,
// "The error a line repeats"): part of that error is fixed by where the dot falls on the pixel
// grid, and a straight stretch of the drive keeps that place. Measured as the correlation of each
// dot's reprojection residuals in consecutive frames, pooled over every dot of every marker.
// Memory: one entry per graph node, sized at start-up; no heap per frame.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/survey/marker_sighting.hpp"

namespace irloc::survey {

class RepeatedShare {
 public:
  explicit RepeatedShare(std::size_t nodes) : last_(nodes) {}  // allocates

  // The sighting of node's marker in `frame`: its dots are compared with those of the node's
  // sighting in the frame before, if there was one.
  void add(int node, const MarkerSighting& sighting, std::uint64_t frame);
  // In [0, 1]; 0 until measured. A negative correlation (errors that average out faster than
  // independent ones) counts as none.
  double share() const;

 private:
  struct LastSighting {
    DotResiduals residuals = DotResiduals::Zero();
    dot::CellMask cells = 0;
    std::uint64_t frame = 0;
  };
  std::vector<LastSighting> last_;
  double products_ = 0;  // sum over dots seen in consecutive frames of their residuals' dot product
  double squares_ = 0;   // ... and of their mean squared norm
};

}  // namespace irloc::survey
