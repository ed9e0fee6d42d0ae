#pragma once
// The outside-in scenes' camera, its lens the intrinsics' model: on a wall, `height` above the floor at (x, y), looking
// along the floor direction `yaw` (from world +x toward +y) and pitched down at the floor.
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include <Eigen/Geometry>

#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/camera_model.hpp"
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
};

// A wall camera's projections, its lens model and pose made once (a CameraModel scans its radial
// map when it is made): for the loops that project many points.
class WallProjection {
 public:
  explicit WallProjection(const WallCamera& camera)
      : model_(camera.intrinsics), world_from_camera_(camera.world_from_camera()), camera_from_world_(world_from_camera_.inverse()) {}

  const CameraIntrinsics& intrinsics() const { return model_.intrinsics(); }
  // The pixel of a world point through the lens; NaN where the lens model does not project it.
  Eigen::Vector2d project(const Eigen::Vector3d& world) const {
    Eigen::Vector2d pixel;
    if (!model_.project(camera_from_world_ * world, pixel)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    return pixel;
  }
  // The camera's centre, world frame.
  const Eigen::Vector3d& origin() const { return world_from_camera_.translation; }
  // The world-frame direction (unit) of the ray through a pixel (in the image or beyond it), if the
  // lens model has one there.
  std::optional<Eigen::Vector3d> ray(double u, double v) const {
    Eigen::Vector3d bearing;
    if (!model_.unproject(Eigen::Vector2d(u, v), bearing)) return std::nullopt;
    return Eigen::Vector3d(world_from_camera_.rotation * bearing);
  }
  // The floor point seen at a pixel, if the lens model has a ray there and it meets the floor.
  std::optional<Eigen::Vector2d> floor_at(double u, double v) const {
    const std::optional<Eigen::Vector3d> through = ray(u, v);
    if (!through || through->z() >= -1e-6) return std::nullopt;
    return (origin() - origin().z() / through->z() * *through).head<2>();
  }

 private:
  CameraModel model_;
  RigidTransform world_from_camera_, camera_from_world_;
};

}  // namespace irloc::sim
