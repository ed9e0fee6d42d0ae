#pragma once
// A rolling shutter exposes image row v of a frame at t_ns + v * line_time (conventions.md), so
// the points a source measures in one frame are seen from the robot at different instants while
// the pose it reports is the one at t_ns. Over the few tens of milliseconds a frame's rows take,
// the robot's motion is taken as constant (FrameMotion). A source moves each mapped point to where
// the robot at t_ns would see what it saw at its row's time, fits the pose to the moved points (the
// pose at t_ns), and reports its observations' pixels moved to t_ns too (what map building,
// calibration and the mount watch consume).

#include <cstdint>
#include <optional>
#include <span>

#include <Eigen/Core>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/source/source_input.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

// Whether `fitted` (a pose at t_ns) lies farther from `prior` than twice what the fastest robot
// (limits) travels or turns in the time between (the margin: both poses' errors): no track then
// describes the frame's motion (a robot carried off, a track gone wrong).
bool beyond_reach(const PosePrior& prior, const RigidTransform& fitted, std::int64_t t_ns, const MotionLimits& limits);

// The track's motion stands for the motion within a frame only while it is fresh: the two poses
// it comes from, and the frame it is used for, each at most this far apart (three pose attempts
// of a 40 fps strobed camera).
inline constexpr std::int64_t kMaxTrackGapNs = 150'000'000;

// Seconds after the frame's t_ns at which a pixel's row was exposed.
inline double row_time(const Eigen::Vector2d& pixel, std::int64_t line_time_ns) {
  return pixel.y() * static_cast<double>(line_time_ns) * 1e-9;
}

// T_W_B dt seconds after world_from_base under `motion`: turned by yaw_rate dt about W's z, moved
// along the arc its heading-frame velocity draws.
RigidTransform pose_after(const RigidTransform& world_from_base, double dt, const FrameMotion& motion);

// The point that the robot at its pose of t_ns (world_from_base) sees where, dt seconds later
// under `motion`, it sees `world`: T_W_B(t_ns) T_W_B(t_ns + dt)^-1 world. Exact for the constant
// motion. Fitting a pose to such points gives the pose at t_ns; the point depends on
// world_from_base only through the turn (a position a centimetre off moves it by yaw_rate dt
// centimetres), so a fit to them converges in two passes.
Eigen::Vector3d point_seen_at_frame_time(const Eigen::Vector3d& world, double dt, const FrameMotion& motion,
                                         const RigidTransform& world_from_base);

// At most how far point_seen_at_frame_time moves a point, for dt up to max_dt, when given
// world_from_base `b` instead of `a`: |position change| * |yaw_rate| max_dt (the turn within the
// frame about another centre) plus |yaw change| * |velocity| max_dt (the travel within the frame in
// another direction), to first order.
double moved_point_change(const RigidTransform& a, const RigidTransform& b, const FrameMotion& motion, double max_dt);

// The constant motion that takes a recent pose to world_from_base at t_ns (the arc through both):
// the track's motion from its last two poses, or, for a frame whose track has no motion yet, from
// the last pose to this frame's own fit. A plain prior is taken as the pose at the time its plain
// fit holds (PosePrior::plain_delay_ns): two plain fits whose markers lie on other rows of their
// frames are apart by the motion over their own times, not their frames'. Empty when prior is
// null, not recent (max_gap_ns) or from the future.
std::optional<FrameMotion> motion_since(const PosePrior* prior, const RigidTransform& world_from_base,
                                        std::int64_t t_ns, std::int64_t max_gap_ns);

// How fast the robot may change its motion. The config bounds the robot's speed and turn (limits),
// not how fast either changes, so these take the fastest robot's steady turn as that rate: its
// velocity turns at max_yaw_rate at max_speed (max_speed * max_yaw_rate m/s^2), and it takes the
// time of a radian at that turn to reach its fastest turn from none (max_yaw_rate^2 rad/s^2).
struct MotionChangeRates {
  double acceleration;      // m/s^2, of the velocity
  double yaw_acceleration;  // rad/s^2, of the yaw rate
};

inline MotionChangeRates fastest_motion_change(const MotionLimits& limits) {
  return {limits.speed * limits.yaw_rate, limits.yaw_rate * limits.yaw_rate};
}

// The prior on the motion within a frame gap_s seconds after the track's last pose: the track's
// motion (`before`, its variances per velocity axis and of the yaw rate), its standard deviations
// grown by what the robot may change in the gap (fastest_motion_change). Empty once either
// standard deviation reaches the fastest robot's (a gap of 1 / max_yaw_rate seconds, 0.64 s by
// default, with an exact track): the fastest robot's prior then says more.
std::optional<MotionPrior> motion_prior_after_gap(const FrameMotion& before, double velocity_variance,
                                                  double yaw_rate_variance, double gap_s, const MotionLimits& limits);

// The motion within the input's frame: the track's, or else the motion since the last pose to
// `fitted` (this frame's own fit, the pose fitted_delay_ns after the frame's t_ns: its mean row
// time for a plain fit); empty when neither is known.
std::optional<FrameMotion> frame_motion(const SourceInput& input, const RigidTransform& fitted,
                                        std::int64_t fitted_delay_ns = 0);

// The pixel at which the camera at t_ns (robot at world_from_base) would have seen what it saw at
// `pixel`, dt seconds later under `motion`, on the horizontal plane z = plane_z (the ceiling the
// point lies on): its ray from the camera at the row's time meets the plane, and that point is
// projected from the camera at t_ns. The pixel itself when the ray misses the plane or the point
// leaves the camera model.
Eigen::Vector2d pixel_at_frame_time(const Eigen::Vector2d& pixel, double dt, const FrameMotion& motion,
                                    const RigidTransform& world_from_base, const RigidTransform& base_from_camera,
                                    const CameraModel& camera, double plane_z);

// With the motion unknown, a pose fitted to points seen mean_dt seconds after t_ns on average may
// be off by up to the fastest robot's (limits) travel and turn in that time: their squares are
// added to the variances of the free position and yaw parameters (rows the dof fixes stay zero).
void add_unknown_motion(double mean_dt, const MotionLimits& limits, PoseCovariance& covariance);

// The result's observations' pixels moved to where the camera at t_ns (the robot at the result's
// pose) would have seen them, under `motion`, each on the horizontal plane of its mapped point.
void observations_to_frame_time(std::int64_t line_time_ns, const FrameMotion& motion, const CameraModel& camera,
                                const RigidTransform& base_from_camera, SourceResult& result);

// For a source whose own solver does not model the row times (the LED source): its
// result's pose moved to t_ns by the change that the observations' row times make to a
// reprojection fit of them (observations: mapped points and pixels), and the observations' pixels
// moved to t_ns (the motion in result.motion_from_track); with the motion unknown,
// add_unknown_motion instead (and the result's pose_delay_ns, for the track). A fit that fails
// leaves the result as it was.
void move_fit_to_frame_time(const SourceInput& input, const CameraModel& camera, const RigidTransform& base_from_camera,
                            Dof dof, SourceResult& result);

}  // namespace irloc
