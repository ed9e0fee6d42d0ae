#pragma once
// Planar PnP problems: a camera at a random pose looking at a patch of a plane (z = 0), the
// patch's points seen through a lens with noise. Shared by planar_pnp_test and its OpenCV oracle.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "tests/geometry/ceiling_scene.hpp"  // rotation_error

namespace irloc::test {

struct PlanarProblem {
  RigidTransform camera_from_plane;
  std::vector<Eigen::Vector2d> plane;
  std::vector<Eigen::Vector2d> pixels;
};

// A camera 1.5-4 m from the patch's centre, its optical axis 0-70 degrees from the plane's
// normal, aimed at the centre with up to 0.15 rad of slack; the patch a grid of columns x rows
// points of pitch `pitch` (4 corners of a tile: 2 x 2). false when a point leaves the image.
inline bool make_planar_problem(const CameraModel& camera, int columns, int rows, double pitch, double sigma,
                                std::mt19937& rng, PlanarProblem& problem) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::normal_distribution<double> noise(0, sigma);
  const Eigen::Vector3d centre(4 * unit(rng) - 2, 4 * unit(rng) - 2, 0);
  const double tilt = 70 * std::numbers::pi / 180 * unit(rng), azimuth = 2 * std::numbers::pi * unit(rng);
  const double range = 1.5 + 2.5 * unit(rng);
  const Eigen::Vector3d position =
      centre + range * Eigen::Vector3d(std::sin(tilt) * std::cos(azimuth), std::sin(tilt) * std::sin(azimuth), std::cos(tilt));
  const Eigen::Vector3d forward = (centre - position).normalized();
  const Eigen::Vector3d helper = std::abs(forward.z()) > 0.99 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d world_from_camera;
  world_from_camera.col(2) = forward;
  world_from_camera.col(0) = forward.cross(helper).normalized();
  world_from_camera.col(1) = world_from_camera.col(2).cross(world_from_camera.col(0));
  const Eigen::Matrix3d slack =
      (Eigen::AngleAxisd(0.15 * (2 * unit(rng) - 1), Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(0.15 * (2 * unit(rng) - 1), Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(std::numbers::pi * (2 * unit(rng) - 1), Eigen::Vector3d::UnitZ())).toRotationMatrix();
  problem.camera_from_plane = RigidTransform{world_from_camera * slack, position}.inverse();
  problem.plane.clear();
  problem.pixels.clear();
  const double turn = 2 * std::numbers::pi * unit(rng);
  const Eigen::Rotation2Dd in_plane(turn);
  for (int i = 0; i < columns; ++i) {
    for (int j = 0; j < rows; ++j) {
      const Eigen::Vector2d point = centre.head<2>() + in_plane * Eigen::Vector2d(pitch * (i - 0.5 * (columns - 1)),
                                                                                  pitch * (j - 0.5 * (rows - 1)));
      Eigen::Vector2d pixel;
      if (!camera.project(problem.camera_from_plane * Eigen::Vector3d(point.x(), point.y(), 0), pixel) ||
          !camera.in_image(pixel))
        return false;
      problem.plane.push_back(point);
      problem.pixels.push_back(pixel + Eigen::Vector2d(noise(rng), noise(rng)));
    }
  }
  return true;
}

inline double centre_error(const RigidTransform& a, const RigidTransform& b) {
  return (a.inverse().translation - b.inverse().translation).norm();
}

}  // namespace irloc::test
