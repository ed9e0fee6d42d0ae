#include "host_sim/scenario/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace irloc::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// Back-and-forth lanes along x across the area, `spacing` apart in y.
std::vector<Eigen::Vector2d> lawn_mower_points(const Eigen::Vector4d& area, double spacing) {
  std::vector<Eigen::Vector2d> points;
  const int lanes = static_cast<int>(std::floor((area[3] - area[1]) / spacing + 1e-9)) + 1;
  for (int lane = 0; lane < lanes; ++lane) {
    const double y = area[1] + lane * spacing;
    const bool forward = lane % 2 == 0;
    points.emplace_back(forward ? area[0] : area[2], y);
    points.emplace_back(forward ? area[2] : area[0], y);
  }
  return points;
}

}  // namespace

Trajectory::Trajectory(const TrajectorySpec& spec) : spec_(spec) {
  if (spec.kind == TrajectoryKind::waypoints) {
    std::vector<Eigen::Vector2d> points = spec.points;
    if (spec.closed) points.push_back(points.front());
    build_polyline(points, spec.speeds, spec.turn_rate);
    repeats_ = spec.closed;
  } else if (spec.kind == TrajectoryKind::lawn_mower) {
    std::vector<Eigen::Vector2d> points = lawn_mower_points(spec.area, spec.spacing);
    // Sweep back to the start so the pattern repeats without a jump.
    points.push_back(points.front());
    build_polyline(points, std::vector<double>(points.size() - 1, spec.speed), spec.turn_rate);
    repeats_ = true;
  } else if (spec.kind == TrajectoryKind::loop) {
    duration_ = 2 * kPi * spec.radius / spec.speed;
    repeats_ = true;
  }
}

void Trajectory::build_polyline(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& speeds,
                                double turn_rate) {
  double t = 0;
  double yaw = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Eigen::Vector2d step = points[i + 1] - points[i];
    if (step.norm() < 1e-9) continue;
    const double heading = std::atan2(step.y(), step.x());
    if (legs_.empty()) {
      yaw = heading;
    } else {
      const double turn = std::remainder(heading - yaw, 2 * kPi);
      if (std::abs(turn) > 1e-9) {
        const double length = std::abs(turn) / turn_rate;
        legs_.push_back({points[i], points[i], yaw, yaw + turn, t, length});
        t += length;
        yaw += turn;
      }
    }
    const double length = step.norm() / speeds[i];
    legs_.push_back({points[i], points[i + 1], yaw, yaw, t, length});
    t += length;
  }
  // A closed path turns back to its first heading before it repeats.
  if (points.size() > 2 && (points.front() - points.back()).norm() < 1e-9 && !legs_.empty()) {
    const double turn = std::remainder(legs_.front().yaw_from - yaw, 2 * kPi);
    if (std::abs(turn) > 1e-9) {
      const double length = std::abs(turn) / turn_rate;
      legs_.push_back({points.back(), points.back(), yaw, yaw + turn, t, length});
      t += length;
    }
  }
  duration_ = t;
}

PlanarPose Trajectory::pose_at(double t) const {
  switch (spec_.kind) {
    case TrajectoryKind::static_pose:
      return {spec_.pose.x(), spec_.pose.y(), wrap_angle(spec_.pose.z())};
    case TrajectoryKind::spin:
      return {spec_.pose.x(), spec_.pose.y(), wrap_angle(spec_.pose.z() + spec_.rate * t)};
    case TrajectoryKind::loop: {
      const double sign = spec_.clockwise ? -1 : 1;
      const double angle = sign * spec_.speed * t / spec_.radius;
      return {spec_.centre.x() + spec_.radius * std::cos(angle), spec_.centre.y() + spec_.radius * std::sin(angle),
              wrap_angle(angle + sign * kPi / 2)};
    }
    case TrajectoryKind::waypoints:
    case TrajectoryKind::lawn_mower:
      break;
  }
  double local = t;
  if (repeats_ && duration_ > 0) local = std::fmod(t, duration_);
  if (local < 0) local = 0;
  const Leg* leg = &legs_.back();
  for (const Leg& candidate : legs_) {
    if (local < candidate.start + candidate.length) {
      leg = &candidate;
      break;
    }
  }
  const double s = std::clamp((local - leg->start) / leg->length, 0.0, 1.0);
  const Eigen::Vector2d p = leg->from + s * (leg->to - leg->from);
  return {p.x(), p.y(), wrap_angle(leg->yaw_from + s * (leg->yaw_to - leg->yaw_from))};
}

Eigen::Isometry3d Trajectory::t_w_b(double t) const {
  const PlanarPose pose = pose_at(t);
  // The sway: roll, pitch and heave at incommensurate phases, so that every combination occurs.
  const double phase = 2 * std::numbers::pi * t / spec_.sway_period;
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.linear() = rotation_from_rpy(spec_.sway_roll * std::sin(phase), spec_.sway_pitch * std::sin(1.618 * phase + 1),
                                         pose.yaw);
  transform.translation() = Eigen::Vector3d(pose.x, pose.y, spec_.sway_heave * std::sin(0.723 * phase + 2));
  return transform;
}

Eigen::Vector2d occluder_position(const Occluder& person, double t) {
  if (person.path.size() == 1 || person.speed == 0) return person.path.front();
  double total = 0;
  for (std::size_t i = 0; i + 1 < person.path.size(); ++i) total += (person.path[i + 1] - person.path[i]).norm();
  if (total == 0) return person.path.front();
  double s = std::fmod(person.speed * t, 2 * total);
  if (s > total) s = 2 * total - s;  // walking back
  for (std::size_t i = 0; i + 1 < person.path.size(); ++i) {
    const double leg = (person.path[i + 1] - person.path[i]).norm();
    if (s <= leg && leg > 0) return person.path[i] + (person.path[i + 1] - person.path[i]) * (s / leg);
    s -= leg;
  }
  return person.path.back();
}

}  // namespace irloc::sim
