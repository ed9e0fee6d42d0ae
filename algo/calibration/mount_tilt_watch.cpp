#include "algo/calibration/mount_tilt_watch.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "algo/geometry/pose_refinement.hpp"

namespace irloc::calibration {
namespace {

constexpr std::size_t kMinPoints = 6;
// The fit's covariance assumes pixel_sigma; it is rescaled to the fit's own residuals, at least
// this many pixels (as the dot source does).
constexpr double kMinPixelSigma = 0.25;

}  // namespace

double MountTilt::sigma() const {
  if (tilt.norm() == 0) return std::sqrt(covariance.trace() / 2);
  const Eigen::Vector2d direction = tilt.normalized();
  return std::sqrt(direction.dot(covariance * direction));
}

MountTiltWatch::MountTiltWatch(const CameraIntrinsics& camera, const RigidTransform& base_from_camera, Dof dof,
                               const MountWatchConfig& config)
    : camera_(camera), base_from_camera_(base_from_camera), config_(config) {
  if (dof == Dof::full6) {
    throw std::invalid_argument("mount_watch: needs a level robot (robot.dof 3 or 4); with dof 6 the mount's tilt "
                                "and the robot's are one");
  }
}

bool MountTiltWatch::update(std::int64_t t_ns, const RigidTransform& world_from_base,
                            std::span<const PointObservation> points) {
  if (points.size() < kMinPoints) return false;
  std::array<Eigen::Vector3d, kMaxPointObservations> world;
  std::array<Eigen::Vector2d, kMaxPointObservations> pixels;
  const std::size_t count = std::min(points.size(), kMaxPointObservations);
  for (std::size_t k = 0; k < count; ++k) {
    world[k] = points[k].world;
    pixels[k] = points[k].pixel;
  }
  RefinementOptions options;
  options.dof = Dof::full6;
  const PoseFit fit = refine_pose({world.data(), count}, {pixels.data(), count}, camera_, base_from_camera_,
                                  world_from_base, options);
  if (!fit.ok) return false;
  const RollPitchYaw rpy = rpy_from_rotation(fit.world_from_base.rotation);
  const Eigen::Vector2d measured(rpy.roll, rpy.pitch);
  const double scale = std::max(fit.rms_px, kMinPixelSigma) / options.pixel_sigma;
  const Eigen::Matrix2d covariance = fit.covariance.block<2, 2>(3, 3) * scale * scale +
                                     Eigen::Matrix2d::Identity() * config_.floor_sigma * config_.floor_sigma;
  const Eigen::Matrix2d measured_information = covariance.inverse();
  if (!measured_information.allFinite()) return false;

  // Exponential forgetting over frame time: older poses weigh exp(-age / time_constant).
  const double dt = state_.poses == 0 ? 0.0 : std::max(0.0, static_cast<double>(t_ns - last_t_ns_) * 1e-9);
  const double keep = state_.poses == 0 ? 0.0 : std::exp(-dt / config_.time_constant);
  information_ = keep * information_ + measured_information;
  information_tilt_ = keep * information_tilt_ + measured_information * measured;
  last_t_ns_ = t_ns;
  ++state_.poses;
  state_.covariance = information_.inverse();
  state_.tilt = state_.covariance * information_tilt_;

  const bool was = state_.warning;
  if (!state_.warning) {
    state_.warning = state_.magnitude() - config_.sigmas * state_.sigma() > config_.tolerance;
  } else {
    state_.warning = state_.magnitude() >= config_.tolerance;
  }
  return state_.warning != was;
}

}  // namespace irloc::calibration
