#pragma once
// Stage 1: which blobs of the strobe difference look like marker dots.
//
// A dot is a small, round blob (area near the expected dot area, low elongation) that is dark in
// the LED-off frame: retro-reflectors shine only under the robot's own LEDs, while lamps and
// glints are bright in both frames and so have a low contrast (on - off) / on.

#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "algo/core/image_view.hpp"
#include "algo/core/static_vector.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/kernels/blob.hpp"
#include "algo/markers/dot/dot_source_config.hpp"
#include "algo/markers/dot/nominal_plane.hpp"

namespace irloc::dot {

struct DotCandidate {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();    // intensity-weighted centroid, px
  Eigen::Vector3d bearing = Eigen::Vector3d::UnitZ();  // unit ray, camera frame
  Eigen::Vector2d plane = Eigen::Vector2d::Zero();    // where the ray meets the nominal ceiling plane, metres
  double mean_intensity = 0;   // mean on - off over the blob, grey levels
  std::uint32_t area = 0;      // pixels
};

inline constexpr std::size_t kMaxDotCandidates = 128;
using DotCandidateList = StaticVector<DotCandidate, kMaxDotCandidates>;

// Why blobs were not taken, for diagnostics.
struct CandidateCounters {
  std::uint32_t blobs = 0;
  std::uint32_t wrong_size = 0;
  std::uint32_t not_round = 0;
  std::uint32_t low_contrast = 0;
  std::uint32_t off_ray = 0;     // outside the lens model or not reaching the ceiling plane
  std::uint32_t dropped = 0;     // did not fit in the candidate list (overflow)
};

class DotCandidateSelector {
 public:
  // expected_area: the area of one dot in pixels at the nominal distance.
  DotCandidateSelector(const DotSourceConfig& config, const CameraModel& camera, const NominalPlane& plane,
                       double expected_area);

  // Clears candidates and fills it from blobs; off is the LED-off frame of the pair (for the
  // contrast test). Allocates nothing.
  CandidateCounters select(const BlobList& blobs, const GrayImageView& off, DotCandidateList& candidates) const;

 private:
  const DotSourceConfig& config_;
  const CameraModel& camera_;
  const NominalPlane& plane_;
  double max_area_ = 0;
};

}  // namespace irloc::dot
