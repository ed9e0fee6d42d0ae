#include "algo/source/rolling_shutter.hpp"

#include <algorithm>
#include <cmath>

#include "algo/core/static_vector.hpp"
#include "algo/geometry/pose_refinement.hpp"

#include <Eigen/Geometry>

namespace irloc {

namespace {

// Along an arc turned by `turn`, the chord is the arc's length times this, in the direction of
// the heading halfway.
double chord_per_arc(double turn) { return std::abs(turn) < 1e-9 ? 1.0 : std::sin(turn / 2) / (turn / 2); }

}  // namespace

RigidTransform pose_after(const RigidTransform& world_from_base, double dt, const FrameMotion& motion) {
  const double turn = motion.yaw_rate * dt;
  const Eigen::Matrix3d halfway = Eigen::AngleAxisd(heading(world_from_base) + turn / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d travel = halfway * motion.velocity * (dt * chord_per_arc(turn));
  return {Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix() * world_from_base.rotation,
          world_from_base.translation + travel};
}

Eigen::Vector3d point_seen_at_frame_time(const Eigen::Vector3d& world, double dt, const FrameMotion& motion,
                                         const RigidTransform& world_from_base) {
  return world_from_base * (pose_after(world_from_base, dt, motion).inverse() * world);
}

double moved_point_change(const RigidTransform& a, const RigidTransform& b, const FrameMotion& motion, double max_dt) {
  const double position = (a.translation - b.translation).norm();
  const double yaw = std::abs(wrap_angle(heading(a) - heading(b)));
  return (position * std::abs(motion.yaw_rate) + yaw * motion.velocity.norm()) * max_dt;
}

bool beyond_reach(const PosePrior& prior, const RigidTransform& fitted, std::int64_t t_ns, const MotionLimits& limits) {
  const double dt = static_cast<double>(t_ns - prior.t_ns) * 1e-9;
  const double turn = std::abs(wrap_angle(heading(fitted) - heading(prior.world_from_base)));
  return (fitted.translation - prior.world_from_base.translation).norm() > 2 * limits.speed * dt ||
         turn > 2 * limits.yaw_rate * dt;
}

std::optional<FrameMotion> motion_since(const PosePrior* prior, const RigidTransform& world_from_base,
                                        std::int64_t t_ns, std::int64_t max_gap_ns) {
  if (prior == nullptr) return std::nullopt;
  const std::int64_t since_ns = prior->t_ns + prior->plain_delay_ns;
  if (t_ns <= since_ns || t_ns - since_ns > max_gap_ns) return std::nullopt;
  const double dt = static_cast<double>(t_ns - since_ns) * 1e-9;
  const double start = heading(prior->world_from_base);
  const double turn = wrap_angle(heading(world_from_base) - start);
  const Eigen::Matrix3d halfway = Eigen::AngleAxisd(start + turn / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d chord = world_from_base.translation - prior->world_from_base.translation;
  return FrameMotion{halfway.transpose() * chord / (dt * chord_per_arc(turn)), turn / dt};
}

std::optional<MotionPrior> motion_prior_after_gap(const FrameMotion& before, double velocity_variance,
                                                  double yaw_rate_variance, double gap_s, const MotionLimits& limits) {
  const MotionChangeRates rates = fastest_motion_change(limits);
  const double velocity_change = rates.acceleration * gap_s, yaw_rate_change = rates.yaw_acceleration * gap_s;
  const double velocity_sigma = std::sqrt(velocity_variance + velocity_change * velocity_change);
  const double yaw_rate_sigma = std::sqrt(yaw_rate_variance + yaw_rate_change * yaw_rate_change);
  if (!(velocity_sigma < limits.speed && yaw_rate_sigma < limits.yaw_rate)) return std::nullopt;
  MotionPrior prior{before, velocity_sigma, std::min(velocity_sigma, fastest_side_speed(limits)), yaw_rate_sigma};
  prior.mean.velocity.z() = 0;  // no climb
  return prior;
}

std::optional<FrameMotion> frame_motion(const SourceInput& input, const RigidTransform& fitted,
                                        std::int64_t fitted_delay_ns) {
  if (input.motion) return input.motion;
  return motion_since(input.prior, fitted, input.on.t_ns + fitted_delay_ns, kMaxTrackGapNs);
}

Eigen::Vector2d pixel_at_frame_time(const Eigen::Vector2d& pixel, double dt, const FrameMotion& motion,
                                    const RigidTransform& world_from_base, const RigidTransform& base_from_camera,
                                    const CameraModel& camera, double plane_z) {
  Eigen::Vector3d bearing;
  if (!camera.unproject(pixel, bearing)) return pixel;
  const RigidTransform world_from_camera_then = pose_after(world_from_base, dt, motion) * base_from_camera;
  const Eigen::Vector3d direction = world_from_camera_then.rotation * bearing;
  const Eigen::Vector3d& origin = world_from_camera_then.translation;
  if (std::abs(direction.z()) < 1e-9) return pixel;
  const double along = (plane_z - origin.z()) / direction.z();
  if (along <= 0) return pixel;
  const Eigen::Vector3d point = origin + along * direction;
  Eigen::Vector2d moved;
  if (!camera.project((world_from_base * base_from_camera).inverse() * point, moved)) return pixel;
  return moved;
}

void add_unknown_motion(double mean_dt, const MotionLimits& limits, PoseCovariance& covariance) {
  const double travel = limits.speed * mean_dt, turn = limits.yaw_rate * mean_dt;
  for (int k : {0, 1, 2}) {
    if (covariance(k, k) > 0) covariance(k, k) += travel * travel;
  }
  if (covariance(5, 5) > 0) covariance(5, 5) += turn * turn;
}

// The observations' fit, once to their mapped points and once to the points the robot at t_ns
// sees where it saw them, from the same pixels: the difference of the two poses is what the row
// times did to the fit, and it is taken off the source's pose (whatever the source's own solver).
// Twice when the motion comes from this frame's own pose (frame_motion), which the first pass
// corrects.
void move_fit_to_frame_time(const SourceInput& input, const CameraModel& camera, const RigidTransform& base_from_camera,
                            Dof dof, SourceResult& result) {
  StaticVector<Eigen::Vector3d, kMaxPointObservations> world;
  StaticVector<Eigen::Vector2d, kMaxPointObservations> pixels;
  for (const PointObservation& point : result.observations) {
    world.push_back(point.world);
    pixels.push_back(point.pixel);
  }
  StaticVector<Eigen::Vector3d, kMaxPointObservations> moved;
  StaticVector<double, kMaxPointObservations> row_times;
  double mean_time = 0;
  for (const Eigen::Vector2d& pixel : pixels) {
    row_times.push_back(row_time(pixel, input.line_time_ns));
    mean_time += row_times.back() / static_cast<double>(pixels.size());
  }
  const RigidTransform found = result.world_from_base;
  // The source's pose is a plain fit: it holds at about the points' mean row time.
  const std::int64_t mean_time_ns = std::llround(mean_time * 1e9);
  std::optional<FrameMotion> motion = frame_motion(input, found, mean_time_ns);
  if (!motion) {
    add_unknown_motion(mean_time, input.limits, result.covariance);
    result.pose_delay_ns = mean_time_ns;
    return;
  }
  RefinementOptions options;
  options.dof = dof;
  options.loss = RobustLoss::none;
  const PoseFit plain = refine_pose({world.begin(), world.size()}, {pixels.begin(), pixels.size()}, camera,
                                    base_from_camera, found, options);
  if (!plain.ok) return;
  // After a plain prior, the arc between the two plain fits, once; else again from the corrected pose.
  const int passes = input.motion || (input.prior != nullptr && input.prior->plain) ? 1 : 2;
  for (int pass = 0; pass < passes; ++pass) {
    moved.clear();
    for (std::size_t k = 0; k < world.size(); ++k) {
      moved.push_back(point_seen_at_frame_time(world[k], row_times[k], *motion, result.world_from_base));
    }
    const PoseFit at_frame_time =
        refine_pose({moved.begin(), moved.size()}, {pixels.begin(), pixels.size()}, camera, base_from_camera,
                    plain.world_from_base, options);
    if (!at_frame_time.ok) return;
    PoseParameters corrected = parameters_from_pose(found) + parameters_from_pose(at_frame_time.world_from_base) -
                               parameters_from_pose(plain.world_from_base);
    for (int angle : {3, 4, 5}) corrected[angle] = wrap_angle(corrected[angle]);
    result.world_from_base = pose_from_parameters(corrected);
    if (pass + 1 < passes) motion = frame_motion(input, result.world_from_base);
  }
  result.motion_from_track = motion;
  observations_to_frame_time(input.line_time_ns, *motion, camera, base_from_camera, result);
}

void observations_to_frame_time(std::int64_t line_time_ns, const FrameMotion& motion, const CameraModel& camera,
                                const RigidTransform& base_from_camera, SourceResult& result) {
  for (PointObservation& point : result.observations) {
    point.pixel = pixel_at_frame_time(point.pixel, row_time(point.pixel, line_time_ns), motion, result.world_from_base,
                                      base_from_camera, camera, point.world.z());
  }
}

}  // namespace irloc
