#pragma once
// irlocd's online watch of the mount's tilt (algo/calibration/mount_tilt_watch.hpp): fed with
// every pose and the points its sources measured; one stderr line when the camera is found off
// its calibrated mount and one when it is back; the status line shows the current tilt.
// on_attempt() allocates nothing.

#include <cstdio>

#include "algo/calibration/mount_tilt_watch.hpp"
#include "algo/pipeline/localizer.hpp"
#include "firmware/frame_loop.hpp"

namespace irloc::firmware {

class MountWatchMonitor final : public AttemptObserver {
 public:
  MountWatchMonitor(const Localizer& localizer, const CameraIntrinsics& camera, const RigidTransform& base_from_camera,
                    Dof dof, const calibration::MountWatchConfig& config, std::FILE* log);

  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                  const PoseEstimate& estimate) override;

  const calibration::MountTilt& state() const { return watch_.state(); }

 private:
  const Localizer& localizer_;
  calibration::MountTiltWatch watch_;
  std::FILE* log_;
  PointObservationList points_;
};

}  // namespace irloc::firmware
