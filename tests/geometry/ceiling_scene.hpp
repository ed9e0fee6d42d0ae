#pragma once
// An upward-looking camera on a ground robot under ceiling markers: the geometry the pose
// solvers are made for.

#include <random>
#include <vector>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::test {

inline constexpr double kCeilingZ = 3.0;

// The `up` mount preset of docs/conventions.md, 0.3 m above the base and 0.1 m forward.
inline RigidTransform up_mount() {
  RigidTransform mount;
  mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation = Eigen::Vector3d(0.1, 0, 0.3);
  return mount;
}

// A 4 x 4 dot grid (pitch 0.04 m) on the ceiling, centred at (x, y).
inline std::vector<Eigen::Vector3d> dot_grid(double x, double y, double yaw) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::Matrix3d rotation = rotation_from_rpy(0, 0, yaw);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      points.push_back(Eigen::Vector3d(x, y, kCeilingZ) + rotation * Eigen::Vector3d(0.04 * i - 0.06, 0.04 * j - 0.06, 0));
    }
  }
  return points;
}

// The four corners of a square of the given side on the ceiling, centred at (x, y).
inline std::vector<Eigen::Vector3d> square(double x, double y, double side) {
  const double h = side / 2;
  return {Eigen::Vector3d(x - h, y - h, kCeilingZ), Eigen::Vector3d(x + h, y - h, kCeilingZ),
          Eigen::Vector3d(x + h, y + h, kCeilingZ), Eigen::Vector3d(x - h, y + h, kCeilingZ)};
}

// Pixels of the points seen from world_from_base, with Gaussian noise of sigma pixels; false if a
// point is not visible.
inline bool observe(const std::vector<Eigen::Vector3d>& points, const CameraModel& camera,
                    const RigidTransform& world_from_base, const RigidTransform& base_from_camera, double sigma,
                    std::mt19937& rng, std::vector<Eigen::Vector2d>& pixels) {
  std::normal_distribution<double> noise(0, sigma);
  const RigidTransform camera_from_world = (world_from_base * base_from_camera).inverse();
  pixels.clear();
  for (const Eigen::Vector3d& point : points) {
    Eigen::Vector2d pixel;
    if (!camera.project(camera_from_world * point, pixel) || !camera.in_image(pixel)) return false;
    pixels.push_back(pixel + Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return true;
}

inline double rotation_error(const RigidTransform& a, const RigidTransform& b) {
  return Eigen::AngleAxisd(a.rotation.transpose() * b.rotation).angle();
}

}  // namespace irloc::test
