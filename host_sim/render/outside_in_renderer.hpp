#pragma once
// Ray-cast outside-in scenes: a camera on a wall looking down at a tiled floor, the box robot in
// its look (RobotLook) with a soft contact shadow, a person (a vertical cylinder) walking through,
// a drifting sun patch, lamp steps and the camera's auto-exposure; 8-bit frames with sensor noise,
// and the truth of every frame. Independent of algo/markers/outside_in (its own intersections):
// the tests' and irloc-sim's oracle. Each pixel's ray is the camera's lens model unprojected
// exactly (CameraModel, checked against OpenCV in camera_model_oracle_test); a pixel the lens
// model does not define is black.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "algo/markers/outside_in/box_silhouette.hpp"
#include "host_sim/render/outside_in_scene.hpp"
#include "host_sim/render/wall_camera.hpp"

namespace irloc::sim {

class SceneRenderer {
 public:
  explicit SceneRenderer(WallCamera camera, outside_in::BoxBody body = {}, unsigned seed = 7)
      : camera_(camera), view_(camera), body_(body), noise_(seed), pixels_(std::size_t(camera.intrinsics.width) * camera.intrinsics.height) {
    rays_.resize(pixels_.size());
    for (int v = 0; v < camera.intrinsics.height; ++v)
      for (int u = 0; u < camera.intrinsics.width; ++u)
        rays_[std::size_t(v) * camera.intrinsics.width + u] = view_.ray(u, v).value_or(Eigen::Vector3d::Zero());
  }

  const WallCamera& camera() const { return camera_; }
  double exposure() const { return exposure_; }
  bool auto_exposure = true;
  double noise_sigma = 1.5;
  RobotLook look;

  // Renders one frame (auto-exposure then follows the frame's mean, as a webcam does).
  const std::vector<std::uint8_t>& render(const SceneState& scene, FrameTruth& truth) {
    return render([&scene](int) { return scene; }, truth);
  }

  // Renders one frame whose row v shows scene_at_row(v): a rolling shutter, each row the scene at
  // its own exposure time. The truth is row 0's (the frame's time, conventions.md).
  template <typename SceneAtRow>
  const std::vector<std::uint8_t>& render(const SceneAtRow& scene_at_row, FrameTruth& truth) {
    const auto& k = camera_.intrinsics;
    const Eigen::Vector3d& origin = view_.origin();
    truth = {};
    const SceneState top = scene_at_row(0);
    truth.robot_whole_in_view = top.robot && whole_in_view(*top.robot);
    std::normal_distribution<double> gauss(0, noise_sigma);
    double sum = 0;
    for (int v = 0; v < k.height; ++v) {
      const SceneState scene = scene_at_row(v);
      for (int u = 0; u < k.width; ++u) {
        const Eigen::Vector3d& ray = rays_[std::size_t(v) * k.width + u];
        const double radiance = ray.isZero() ? 0.0 : shade(scene, origin, ray, truth);
        const double value = std::clamp(radiance * exposure_ + gauss(noise_), 0.0, 255.0);
        pixels_[std::size_t(v) * k.width + u] = static_cast<std::uint8_t>(std::lround(value));
        sum += value;
      }
    }
    if (auto_exposure) {
      const double mean = sum / pixels_.size();
      exposure_ *= 1 + 0.35 * (kTargetMean / std::max(mean, 1.0) - 1);
    }
    return pixels_;
  }

 private:
  static constexpr double kTargetMean = 120;

  bool whole_in_view(const outside_in::FloorPose& pose) const {
    for (int sx = -1; sx <= 1; sx += 2)
      for (int sy = -1; sy <= 1; sy += 2)
        for (double z : {0.0, body_.height}) {
          const double bx = 0.5 * sx * body_.length, by = 0.5 * sy * body_.width;
          const Eigen::Vector3d p(pose.x + std::cos(pose.yaw) * bx - std::sin(pose.yaw) * by,
                                  pose.y + std::sin(pose.yaw) * bx + std::cos(pose.yaw) * by, z);
          const Eigen::Vector2d px = view_.project(p);
          if (!px.allFinite() || px.x() < 3 || px.y() < 3 || px.x() > camera_.intrinsics.width - 4 || px.y() > camera_.intrinsics.height - 4)
            return false;
        }
    return true;
  }

  // Distance along the ray to the box and the face's shade, or infinity.
  double hit_box(const outside_in::FloorPose& pose, const Eigen::Vector3d& origin, const Eigen::Vector3d& ray, double& shade) const {
    const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
    const Eigen::Vector3d o(c * (origin.x() - pose.x) + s * (origin.y() - pose.y),
                            -s * (origin.x() - pose.x) + c * (origin.y() - pose.y), origin.z());
    const Eigen::Vector3d d(c * ray.x() + s * ray.y(), -s * ray.x() + c * ray.y(), ray.z());
    const Eigen::Vector3d lo(-body_.length / 2, -body_.width / 2, 0), hi(body_.length / 2, body_.width / 2, body_.height);
    double t_near = -1e9, t_far = 1e9;
    int axis = -1;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(d(a)) < 1e-12) {
        if (o(a) < lo(a) || o(a) > hi(a)) return INFINITY;
        continue;
      }
      double t0 = (lo(a) - o(a)) / d(a), t1 = (hi(a) - o(a)) / d(a);
      if (t0 > t1) std::swap(t0, t1);
      if (t0 > t_near) { t_near = t0; axis = a; }
      t_far = std::min(t_far, t1);
    }
    if (t_near > t_far || t_near <= 0) return INFINITY;
    const Eigen::Vector3d p = o + t_near * d;
    if (axis == 2) shade = look.top;
    else if (axis == 1) shade = look.sides;
    else if (p.x() < 0) shade = look.back;
    else if (p.z() >= look.strip_from * body_.height && p.z() < look.strip_to * body_.height) shade = look.strip_shade;
    else shade = look.front;
    return t_near;
  }

  double hit_person(const Person& person, const Eigen::Vector3d& origin, const Eigen::Vector3d& ray, double& shade) const {
    const Eigen::Vector2d o = origin.head<2>() - person.position;
    const Eigen::Vector2d d = ray.head<2>();
    const double a = d.squaredNorm(), b = 2 * o.dot(d), c = o.squaredNorm() - person.radius * person.radius;
    const double disc = b * b - 4 * a * c;
    if (a < 1e-12 || disc < 0) return INFINITY;
    const double t = (-b - std::sqrt(disc)) / (2 * a);
    const double z = origin.z() + t * ray.z();
    if (t <= 0 || z < 0 || z > person.height) return INFINITY;
    shade = z > 0.9 ? 215 : 35;  // light shirt, dark trousers
    return t;
  }

  double floor_albedo(const Eigen::Vector2d& p) const {
    constexpr double kTile = kFloorTile, kGrout = 0.012;
    const double fx = p.x() / kTile - std::floor(p.x() / kTile), fy = p.y() / kTile - std::floor(p.y() / kTile);
    if (fx * kTile < kGrout || fy * kTile < kGrout) return 95;
    const int parity = (static_cast<int>(std::floor(p.x() / kTile)) + static_cast<int>(std::floor(p.y() / kTile))) & 1;
    return (parity ? 150 : 175) + 6 * std::sin(7.1 * p.x()) * std::sin(5.3 * p.y());
  }

  double shade(const SceneState& scene, const Eigen::Vector3d& origin, const Eigen::Vector3d& ray, FrameTruth& truth) const {
    double robot_shade = 0, person_shade = 0;
    // Through a pointer: aarch64 GCC 12 cannot follow the optional's engaged flag through the
    // inlined hit test and warns that the person's fields may be uninitialized.
    const Person* person = scene.person.has_value() ? &scene.person.value() : nullptr;
    const double t_robot = scene.robot ? hit_box(*scene.robot, origin, ray, robot_shade) : INFINITY;
    const double t_person = person ? hit_person(*person, origin, ray, person_shade) : INFINITY;
    if (std::isfinite(t_robot)) {
      ++truth.robot_pixels;
      if (t_person < t_robot) ++truth.robot_hidden_pixels;
    }
    if (std::isfinite(t_person) && t_person < t_robot) return person_shade * scene.lamp;
    if (std::isfinite(t_robot)) return robot_shade * scene.lamp;
    if (ray.z() >= 0) return 90 * scene.lamp;  // the far wall
    const Eigen::Vector2d p = (origin + (-origin.z() / ray.z()) * ray).head<2>();
    double irradiance = 1 + scene.sun_strength * std::exp(-(p - scene.sun).squaredNorm() / (2 * 0.35 * 0.35));
    if (scene.robot) {  // soft contact shadow around the footprint
      const outside_in::FloorPose& r = *scene.robot;
      const double c = std::cos(r.yaw), s = std::sin(r.yaw);
      const Eigen::Vector2d q(c * (p.x() - r.x) + s * (p.y() - r.y), -s * (p.x() - r.x) + c * (p.y() - r.y));
      const double dx = std::max(std::abs(q.x()) - body_.length / 2, 0.0), dy = std::max(std::abs(q.y()) - body_.width / 2, 0.0);
      irradiance *= 1 - 0.45 * std::exp(-std::hypot(dx, dy) / 0.03);
    }
    if (person) irradiance *= 1 - 0.3 * std::exp(-std::max((p - person->position).norm() - person->radius, 0.0) / 0.05);
    return floor_albedo(p) * irradiance * scene.lamp;
  }

  WallCamera camera_;
  WallProjection view_;
  outside_in::BoxBody body_;
  std::mt19937 noise_;
  std::vector<std::uint8_t> pixels_;
  std::vector<Eigen::Vector3d> rays_;  // per pixel, world frame, unit; zero where the lens model has none
  double exposure_ = 1.0;
};

}  // namespace irloc::sim
