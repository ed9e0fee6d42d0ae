#pragma once
// The online watch of the camera mount's tilt (docs/calibration.md, "Mount watch"). A robot of
// dof 3 or 4 is level, so a pose refined in all six degrees of freedom from the points a source
// measured (dots, square corners) tilts only by the mount's error plus the floor's roughness. A
// slow, information-weighted average of that tilt, with its covariance, tells when the camera has
// been knocked out of its calibration: the warning starts when the tilt exceeds the tolerance by
// `sigmas` of its own uncertainty, and clears when it is back under the tolerance.
// Everything is fixed-size: update() allocates nothing and its work is bounded by the points.

#include <cstdint>
#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::calibration {

struct MountWatchConfig {
  bool enabled = true;
  double tolerance = 0.0035;    // rad (0.2 deg): moves a pose by 8 mm under a ceiling 2.3 m up
  double time_constant = 60.0;  // s of frame time: the memory of the average
  double sigmas = 4.0;          // how far beyond the tolerance, in sigmas of the average
  double floor_sigma = 0.005;   // rad: how much a level robot rocks on its floor, per pose
};

struct MountTilt {
  Eigen::Vector2d tilt = Eigen::Vector2d::Zero();  // (roll, pitch) of the mount's error, base axes, rad
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  std::uint64_t poses = 0;  // poses averaged so far
  bool warning = false;
  // The tilt's size and its sigma along the tilt's direction, rad.
  double magnitude() const { return tilt.norm(); }
  double sigma() const;
};

class MountTiltWatch {
 public:
  // Throws std::invalid_argument for dof 6: the mount's tilt cannot be told from the robot's.
  MountTiltWatch(const CameraIntrinsics& camera, const RigidTransform& base_from_camera, Dof dof,
                 const MountWatchConfig& config);

  // One pose (T_W_B as the source reported it) with the points it was measured from. Poses from
  // fewer than 6 points are skipped. Returns true when the warning started or cleared.
  bool update(std::int64_t t_ns, const RigidTransform& world_from_base, std::span<const PointObservation> points);

  const MountTilt& state() const { return state_; }
  const MountWatchConfig& config() const { return config_; }

 private:
  CameraModel camera_;
  RigidTransform base_from_camera_;
  MountWatchConfig config_;
  MountTilt state_;
  Eigen::Matrix2d information_ = Eigen::Matrix2d::Zero();
  Eigen::Vector2d information_tilt_ = Eigen::Vector2d::Zero();
  std::int64_t last_t_ns_ = 0;
};

}  // namespace irloc::calibration
