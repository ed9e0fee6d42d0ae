#pragma once
// What one pose attempt produces: a row of the pose CSV, a message on the serial line.

#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "algo/source/source_kind.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

// The track's motion at a pose: the arc through it and the Localizer's last pose, when that pose
// is recent (rolling_shutter.hpp's kMaxTrackGapNs) and neither is a plain fit of a moving rolling
// shutter frame.
struct PoseVelocity {
  Eigen::Vector3d world = Eigen::Vector3d::Zero();  // of B's origin, in W, m/s
  double yaw_rate = 0;                              // about W's z, rad/s
  // Of (vx, vy, vz, yaw_rate): the two poses' position and yaw covariances, taken as independent,
  // over dt^2.
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
};

struct PoseEstimate {
  std::uint64_t seq = 0;  // of the LED-on frame the pose was computed from
  std::int64_t t_ns = 0;
  bool ok = false;        // false: nothing trustworthy, the pose fields mean nothing
  // T_W_B: position in metres, orientation R_W_B = Rz(yaw) Ry(pitch) Rx(roll) in radians.
  double x = 0, y = 0, z = 0, roll = 0, pitch = 0, yaw = 0;
  int marker_id = -1;     // the dot marker's ID, or -1
  double confidence = 0;  // in [0, 1]; 0 when not ok
  SourceKind source = SourceKind::dot;
  // Of (x, y, z, roll, pitch, yaw) in W, from the solver of the source (or the fusion) at its
  // solution; the rows of parameters the dof fixes are zero. Zero when not ok.
  PoseCovariance covariance = PoseCovariance::Zero();
  std::optional<PoseVelocity> velocity;  // empty when not ok, or the track has no recent pose
  // Under a rolling shutter, a pose whose frame's motion the poses before it did not tell (a
  // drive's first pose: a plain fit, or the pose at t_ns by the motion its own frame shows, which
  // one dot marker leaves to the fastest robot's prior; SourceResult::plain). The next attempt may
  // give it again, better (Localizer::revised_previous): irlocd's pose outputs hold it one attempt
  // for that.
  bool revisable = false;
};

}  // namespace irloc
