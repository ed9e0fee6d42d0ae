#pragma once
// The robot's ground-truth path: T_W_B as a function of time, from a scenario's trajectory.
// The base stays on the floor plane z = 0 with roll = pitch = 0, unless the spec adds a sway.

#include <vector>

#include <Eigen/Geometry>

#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

struct PlanarPose {
  double x = 0, y = 0, yaw = 0;  // metres, radians (yaw wrapped to (-pi, pi])
};

class Trajectory {
 public:
  explicit Trajectory(const TrajectorySpec& spec);

  // The pose at `t` seconds after the start. Open paths hold their last pose; closed paths and
  // lawn-mower sweeps repeat.
  PlanarPose pose_at(double t) const;
  Eigen::Isometry3d t_w_b(double t) const;

  // Seconds one pass of the path takes (0 for static and spin).
  double duration() const { return duration_; }

 private:
  // A piece of a polyline path: driving straight at constant heading, or turning in place.
  struct Leg {
    Eigen::Vector2d from, to;
    double yaw_from = 0, yaw_to = 0;
    double start = 0, length = 0;  // seconds
  };
  void build_polyline(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& speeds, double turn_rate);

  TrajectorySpec spec_;
  std::vector<Leg> legs_;
  double duration_ = 0;
  bool repeats_ = false;
};

// Where a person stands at time t: walking back and forth along the path at constant speed.
Eigen::Vector2d occluder_position(const Occluder& person, double t);

}  // namespace irloc::sim
