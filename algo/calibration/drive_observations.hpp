#pragma once
// What a drive under mapped dot markers gives the calibration: per pose attempt that found a
// pose, its time, the pose the localizer computed with the input calibration (the starting
// point), and every dot it measured (pixel + the map's world point).
// Collected at run time, used once at the end of the drive: heap-backed, not per-frame code.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::calibration {

struct DriveFrame {
  std::int64_t t_ns = 0;
  RigidTransform world_from_base;  // T_W_B with the input calibration
  std::size_t first = 0;           // its dots: observations[first, first + count)
  std::size_t count = 0;
};

class DriveObservations {
 public:
  // At most max_frames frames are kept; later ones are counted in frames_dropped() (a drive of
  // 5000 pose attempts with 30 dots each is 150 000 dots, a few megabytes).
  explicit DriveObservations(std::size_t max_frames = 5000) : max_frames_(max_frames) {}

  // Frames must come in time order. Frames with fewer than 4 dots are not kept.
  void add(std::int64_t t_ns, const RigidTransform& world_from_base, std::span<const PointObservation> dots);

  std::span<const DriveFrame> frames() const { return frames_; }
  std::span<const PointObservation> observations() const { return observations_; }
  std::size_t frames_dropped() const { return frames_dropped_; }

 private:
  std::size_t max_frames_;
  std::vector<DriveFrame> frames_;
  std::vector<PointObservation> observations_;
  std::size_t frames_dropped_ = 0;
};

}  // namespace irloc::calibration
