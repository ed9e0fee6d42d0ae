#include "firmware/mount_watch_monitor.hpp"
#include "firmware/warning_log.hpp"

#include <numbers>

namespace irloc::firmware {

MountWatchMonitor::MountWatchMonitor(const Localizer& localizer, const CameraIntrinsics& camera,
                                     const RigidTransform& base_from_camera, Dof dof,
                                     const calibration::MountWatchConfig& config, std::FILE* log)
    : localizer_(localizer), watch_(camera, base_from_camera, dof, config), log_(log) {}

void MountWatchMonitor::on_attempt(const StrobePair& pair, std::optional<StrobeVerdict>, bool computed,
                                   const PoseEstimate& estimate) {
  if (!computed || !estimate.ok) return;
  points_.clear();
  for (const SourceResult& result : localizer_.last_results()) {
    if (!result.ok || !result.at_frame_time()) continue;
    for (const PointObservation& point : result.observations) {
      if (!points_.push_back(point)) break;
    }
  }
  const RigidTransform world_from_base{rotation_from_rpy(estimate.roll, estimate.pitch, estimate.yaw),
                                       Eigen::Vector3d(estimate.x, estimate.y, estimate.z)};
  if (!watch_.update(pair.on.t_ns, world_from_base, {points_.begin(), points_.size()})) return;
  constexpr double kDegree = std::numbers::pi / 180;
  const calibration::MountTilt& tilt = watch_.state();
  if (tilt.warning) {
    print_warning(log_,
                 "mount watch: at frame %llu the camera is tilted %.2f deg (roll %.2f, pitch %.2f, sigma %.2f) "
                 "off its calibrated mount: poses are off by about that tilt times the ceiling height; recalibrate "
                 "(irlocd --calibrate)",
                 static_cast<unsigned long long>(pair.on.seq), tilt.magnitude() / kDegree, tilt.tilt.x() / kDegree, tilt.tilt.y() / kDegree, tilt.sigma() / kDegree);
  } else {
    print_warning(log_,
                 "mount watch: at frame %llu the camera's tilt is back within %.2f deg of its calibrated mount "
                 "(%.2f deg)",
                 static_cast<unsigned long long>(pair.on.seq), watch_.config().tolerance / kDegree,
                 tilt.magnitude() / kDegree);
  }
  std::fflush(log_);
}

}  // namespace irloc::firmware
