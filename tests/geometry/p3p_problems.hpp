#pragma once
// Random P3P problems with known answers, shared by the P3P tests and benchmark.

#include <array>
#include <random>

#include <Eigen/Geometry>

#include "algo/geometry/p3p.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::test {

struct P3PProblem {
  std::array<Eigen::Vector3d, 3> world;
  std::array<Eigen::Vector3d, 3> bearings;  // unit, camera frame
  RigidTransform camera_from_world;         // the truth, T_C_W
};

// Three points seen within half_angle of the optical axis at depths in [min_depth, max_depth],
// from a uniformly random camera pose near the origin.
class P3PProblemGenerator {
 public:
  explicit P3PProblemGenerator(unsigned seed, double half_angle = 1.0, double min_depth = 0.5,
                               double max_depth = 10)
      : rng_(seed), half_angle_(half_angle), min_depth_(min_depth), max_depth_(max_depth) {}

  P3PProblem next() {
    P3PProblem problem;
    const Eigen::Quaterniond q(normal_(rng_), normal_(rng_), normal_(rng_), normal_(rng_));
    RigidTransform world_from_camera{q.normalized().toRotationMatrix(),
                                     Eigen::Vector3d(uniform_(rng_), uniform_(rng_), uniform_(rng_)) * 5};
    for (int i = 0; i < 3; ++i) {
      const double theta = half_angle_ * std::sqrt(unit_(rng_)), phi = 2 * M_PI * unit_(rng_);
      problem.bearings[i] = Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                            std::cos(theta));
      const double depth = min_depth_ + (max_depth_ - min_depth_) * unit_(rng_);
      problem.world[i] = world_from_camera * (depth * problem.bearings[i]);
    }
    problem.camera_from_world = world_from_camera.inverse();
    return problem;
  }

 private:
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0, 1};
  std::uniform_real_distribution<double> uniform_{-1, 1};
  std::uniform_real_distribution<double> unit_{0, 1};
  double half_angle_, min_depth_, max_depth_;
};

// Largest angle (radians) between a solution's rays to the world points and the bearings.
inline double worst_bearing_error(const P3PProblem& problem, const RigidTransform& camera_from_world) {
  double worst = 0;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d ray = camera_from_world * problem.world[i];
    worst = std::max(worst, std::atan2(ray.cross(problem.bearings[i]).norm(), ray.dot(problem.bearings[i])));
  }
  return worst;
}

// Distance of a pose from the truth: rotation (Frobenius) plus translation relative to the scene.
inline double pose_error(const P3PProblem& problem, const RigidTransform& camera_from_world) {
  const double scale = 1 + (problem.world[0] - problem.camera_from_world.inverse().translation).norm();
  return (camera_from_world.rotation - problem.camera_from_world.rotation).norm() +
         (camera_from_world.translation - problem.camera_from_world.translation).norm() / scale;
}

inline bool contains_truth(const P3PProblem& problem, const P3PSolutions& solutions, double tolerance) {
  for (const RigidTransform& solution : solutions) {
    if (pose_error(problem, solution) < tolerance) return true;
  }
  return false;
}

}  // namespace irloc::test
