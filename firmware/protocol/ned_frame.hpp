#pragma once
// The pose in the local NED frame an autopilot's external navigation input expects
// (docs/hardware.md, "Frames on the MAVLink stream").
//
// World W is z up; NED is z down. irloc maps W to NED by a half turn about W's x axis:
//   north = x_W,  east = -y_W,  down = -z_W,
// and the body frame B (x forward, y left, z up) to FRD (x forward, y right, z down) the same
// way. Then R_NED_FRD = F R_W_B F with F = diag(1, -1, -1), whose Z-Y-X Euler angles are
//   roll_ned = roll,  pitch_ned = -pitch,  yaw_ned = -yaw.
// A robot facing W's +x reports heading 0 (north); turning left (counter-clockwise seen from
// above, yaw_W increasing) lowers the NED heading, as a compass does.

#include <Eigen/Geometry>

#include "algo/pipeline/pose_estimate.hpp"

namespace irloc::firmware {

struct NedPose {
  double north = 0, east = 0, down = 0;  // metres
  double roll = 0, pitch = 0, yaw = 0;   // radians, yaw in (-pi, pi]
};

NedPose ned_from_world(const PoseEstimate& estimate);

// The pose covariance carried into NED: the map above is linear, diag(1, -1, -1) on position
// and on (roll, pitch, yaw), so C_NED = A C A with A = diag(1, -1, -1, 1, -1, -1): the variances
// stay, the x-y and x-yaw cross terms change sign.
PoseCovariance ned_covariance(const PoseCovariance& world);

// R_NED_FRD as a unit quaternion (w, x, y, z as MAVLink orders it).
Eigen::Quaterniond ned_attitude(const NedPose& ned);

// The track's velocity in the body frame FRD (ODOMETRY's child frame): v_FRD = F R_W_B^T v_W, with
// its covariance carried the same way. The rate of the NED heading is -yaw_rate (about the
// vertical: the body's z rate for a level robot).
struct FrdVelocity {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
  double heading_rate = 0;                             // rad/s
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();  // of (vx, vy, vz, heading_rate)
};
FrdVelocity frd_velocity(const PoseEstimate& estimate, const PoseVelocity& velocity);

}  // namespace irloc::firmware
