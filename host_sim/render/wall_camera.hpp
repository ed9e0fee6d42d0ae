#pragma once
// The outside-in scenes' camera: a pinhole on a wall, `height` above the floor at (x, y), looking
// along the floor direction `yaw` (from world +x toward +y) and pitched down at the floor.
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::sim {

struct WallCamera {
  CameraIntrinsics intrinsics{640, 480, 500, 500, 319.5, 239.5, LensModel::plumb_bob, {}};
  double height = 2.4;     // m above the floor
  double pitch_deg = 38;   // down from horizontal
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // m, on the floor plane
  double yaw_deg = 0;      // the direction it looks, from world +x toward +y

  RigidTransform world_from_camera() const {
    const double p = pitch_deg * std::numbers::pi / 180;
    Eigen::Matrix3d r;  // looking along +x
    r.col(0) = Eigen::Vector3d(0, -1, 0);                            // image right
    r.col(1) = Eigen::Vector3d(-std::sin(p), 0, -std::cos(p));       // image down
    r.col(2) = Eigen::Vector3d(std::cos(p), 0, -std::sin(p));        // optical axis
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(yaw_deg * std::numbers::pi / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return {turn * r, Eigen::Vector3d(position.x(), position.y(), height)};
  }
  Eigen::Vector2d project(const Eigen::Vector3d& world) const {
    const Eigen::Vector3d c = world_from_camera().inverse() * world;
    return {intrinsics.fx * c.x() / c.z() + intrinsics.cx, intrinsics.fy * c.y() / c.z() + intrinsics.cy};
  }
};

}  // namespace irloc::sim
