#include "algo/calibration/drive_observations.hpp"

namespace irloc::calibration {

void DriveObservations::add(std::int64_t t_ns, const RigidTransform& world_from_base,
                            std::span<const PointObservation> dots) {
  if (dots.size() < 4) return;
  if (frames_.size() >= max_frames_) {
    ++frames_dropped_;
    return;
  }
  frames_.push_back({t_ns, world_from_base, observations_.size(), dots.size()});
  observations_.insert(observations_.end(), dots.begin(), dots.end());
}

}  // namespace irloc::calibration
