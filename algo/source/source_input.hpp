#pragma once
// What every pose source is handed for one pose attempt: the frame the pose is for and, in
// strobed mode, its LED-off partner and the pair's shared pass. The Localizer checks both frames
// once before any source runs: same pixel depth, the calibrated size. A source never sees a frame
// it would have to refuse for its size.

#include <algorithm>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "algo/frames/frame.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "algo/source/frame_motion.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

// The Localizer's last pose (of any source, fused), for sources that must tell apart landmarks
// that look alike (two squares of one dash pattern) or identify a marker from where the track
// puts it (the dot source, track_identification.hpp).
struct PosePrior {
  RigidTransform world_from_base;
  std::int64_t t_ns = 0;  // of the frame it was found in
  // Under a rolling shutter with the motion unknown: the plain fit, not the pose at t_ns (about
  // the pose at plain_delay_ns after it; with the next frame's plain fit, the motion between them).
  bool plain = false;
  // A plain fit holds about this long after t_ns (the mean row time of the points it was fitted
  // to: SourceResult::plain_delay_ns); 0 otherwise.
  std::int64_t plain_delay_ns = 0;
  PoseCovariance covariance = PoseCovariance::Zero();  // the pose's, as reported
};

// The fastest robot the config describes (robot.max_speed, robot.max_yaw_rate,
// robot.max_side_speed; docs/config.md): how far a pose may move within a frame when nothing says
// how it moved, and how far a track's poses may lie apart.
struct MotionLimits {
  double speed = 1.0;                       // m/s
  double yaw_rate = 1.5707963267948966;     // rad/s (90 deg/s)
  // m/s, the base origin's fastest drive along base y (sideways), at most speed; empty: speed (a
  // robot that may drive any way). A robot on wheels that do not slide, its base origin on their
  // axle, drives sideways only as fast as they slip.
  std::optional<double> side_speed = std::nullopt;
};

// The fastest sideways drive of the base origin (MotionLimits::side_speed).
inline double fastest_side_speed(const MotionLimits& limits) {
  return limits.side_speed ? std::min(*limits.side_speed, limits.speed) : limits.speed;
}

// A prior on the motion within a frame: its mean and the standard deviations of the velocity
// along the heading (forward) and across it (sideways) and of the yaw rate. Where nothing is known
// of the motion, the fastest robot's (fastest_robot_prior); after a gap the track did not bridge,
// the motion before it, its uncertainty grown with the gap (rolling_shutter.hpp,
// motion_prior_after_gap).
struct MotionPrior {
  FrameMotion mean;
  double velocity_sigma = MotionLimits{}.speed;       // m/s, forward
  double side_velocity_sigma = MotionLimits{}.speed;  // m/s, sideways
  double yaw_rate_sigma = MotionLimits{}.yaw_rate;    // rad/s
};

// Zero mean, the fastest robot's speed (sideways, its side speed) and yaw rate as the standard
// deviations.
inline MotionPrior fastest_robot_prior(const MotionLimits& limits) {
  return {FrameMotion{}, limits.speed, fastest_side_speed(limits), limits.yaw_rate};
}

struct SourceInput {
  const Frame& on;    // the LED-on frame (in outside-in mode: the one frame)
  const Frame* off;   // its LED-off partner; nullptr when it has none
  // With off: the pair's one shared pass (pair_pass.hpp), already run by the Localizer: the noise
  // of the difference, the threshold and blobs, the strobe counts. A source that needs its blobs at
  // another threshold may relabel it (the blobs then change for the sources after it).
  PairPass* pair = nullptr;
  const PosePrior* prior = nullptr;  // nullptr until the Localizer has found a pose
  // The frame's rolling shutter: image row v was exposed at on.t_ns + v * line_time_ns
  // (conventions.md); 0: a global shutter. The pose is the one at on.t_ns.
  std::int64_t line_time_ns = 0;
  // The track's motion (the Localizer's last two poses, when recent); empty: unknown.
  std::optional<FrameMotion> motion = std::nullopt;
  // With motion: its uncertainty from the two poses' covariances, the variance of a velocity axis
  // ((m/s)^2, at most the x-y block's trace) and of the yaw rate ((rad/s)^2).
  double motion_velocity_variance = 0;
  double motion_yaw_rate_variance = 0;
  // Without the track's motion: the motion before a gap the track did not bridge, as a prior;
  // empty: the fastest robot's (fastest_robot_prior of limits).
  std::optional<MotionPrior> motion_prior = std::nullopt;
  MotionLimits limits = {};  // the Localizer's setup's
};

// The prior on a frame's motion where the track gives none: the motion before a gap when there
// was one (SourceInput::motion_prior), else the fastest robot's.
inline MotionPrior frame_motion_prior(const SourceInput& input) {
  return input.motion_prior.value_or(fastest_robot_prior(input.limits));
}

}  // namespace irloc
