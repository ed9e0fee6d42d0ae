#pragma once
// A test scene for the dot path: a level robot under a ceiling of dot markers, rendered as a
// strobe pair with an ideal pinhole written here (independent of algo/geometry's camera model):
// discs of the right size at their projected positions, 4 x 4 supersampled, sensor noise, lamps
// bright in both frames and stray reflectors.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "algo/core/image.hpp"
#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/frames/strobe_pairer.hpp"

namespace irloc::test {

inline CameraIntrinsics pinhole_camera(int width = 640, int height = 480, double f = 500) {
  CameraIntrinsics camera;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = f;
  camera.cx = (width - 1) / 2.0;
  camera.cy = (height - 1) / 2.0;
  return camera;
}

// T_B_C of the `up` preset (docs/conventions.md) at xyz.
inline Eigen::Isometry3d up_mount(const Eigen::Vector3d& xyz) {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation() = xyz;
  return mount;
}

inline Eigen::Isometry3d level_pose(double x, double y, double yaw) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation_from_rpy(0, 0, yaw);
  pose.translation() = Eigen::Vector3d(x, y, 0);
  return pose;
}

struct Disc {
  Eigen::Vector3d centre_w;
  double radius = 0.01;
  double on_level = 0;   // added to the LED-on frame
  double off_level = 0;  // added to the LED-off frame
};

struct Scene {
  CameraIntrinsics camera = pinhole_camera();
  Eigen::Isometry3d mount = up_mount({0.1, 0.0, 0.3});
  Eigen::Isometry3d world_from_base = level_pose(0, 0, 0);
  std::vector<Disc> discs;
  double background_on = 30, background_off = 25;
  double noise_sigma = 2.0;
  unsigned seed = 1;

  Eigen::Isometry3d camera_from_world() const { return (world_from_base * mount).inverse(); }

  // Pinhole projection; false behind the camera.
  bool project(const Eigen::Vector3d& world, Eigen::Vector2d& pixel) const {
    const Eigen::Vector3d c = camera_from_world() * world;
    if (c.z() <= 0) return false;
    pixel = {camera.fx * c.x() / c.z() + camera.cx, camera.fy * c.y() / c.z() + camera.cy};
    return true;
  }

  void add_marker(const DotMarker& marker, double level = 150) {
    const dot::CellMask cells = dot::cells_from_id(marker.id);
    for (int cell = 0; cell < dot::kCellCount; ++cell) {
      if ((cells >> cell) & 1u) discs.push_back({dot::cell_in_world(marker, cell), marker.radius, level, 0});
    }
  }

  // Renders the LED-on and LED-off frames (8-bit).
  void render(Image8& on, Image8& off) const {
    on = Image8(camera.width, camera.height);
    off = Image8(camera.width, camera.height);
    std::vector<double> on_level(static_cast<std::size_t>(camera.width * camera.height), background_on);
    std::vector<double> off_level(on_level.size(), background_off);
    const Eigen::Isometry3d c_w = camera_from_world();
    for (const Disc& disc : discs) {
      Eigen::Vector2d centre;
      if (!project(disc.centre_w, centre)) continue;
      // The ceiling is parallel to the image plane for a level robot: the disc images as a circle.
      const double radius_px = camera.fx * disc.radius / (c_w * disc.centre_w).z();
      const int x0 = std::max(0, static_cast<int>(centre.x() - radius_px - 2));
      const int x1 = std::min(camera.width - 1, static_cast<int>(centre.x() + radius_px + 2));
      const int y0 = std::max(0, static_cast<int>(centre.y() - radius_px - 2));
      const int y1 = std::min(camera.height - 1, static_cast<int>(centre.y() + radius_px + 2));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          int inside = 0;
          for (int sy = 0; sy < 4; ++sy) {
            for (int sx = 0; sx < 4; ++sx) {
              const double px = x - 0.375 + 0.25 * sx, py = y - 0.375 + 0.25 * sy;
              if (std::hypot(px - centre.x(), py - centre.y()) <= radius_px) ++inside;
            }
          }
          const std::size_t i = static_cast<std::size_t>(y * camera.width + x);
          on_level[i] += disc.on_level * inside / 16.0;
          off_level[i] += disc.off_level * inside / 16.0;
        }
      }
    }
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0.0, noise_sigma);
    for (int y = 0; y < camera.height; ++y) {
      for (int x = 0; x < camera.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * camera.width + x);
        on.view().at(x, y) = static_cast<std::uint8_t>(std::clamp(std::lround(on_level[i] + noise(random)), 0L, 255L));
        off.view().at(x, y) = static_cast<std::uint8_t>(std::clamp(std::lround(off_level[i] + noise(random)), 0L, 255L));
      }
    }
  }
};

inline StrobePair strobe_pair(const Image8& on, const Image8& off, std::uint64_t seq = 1) {
  StrobePair pair;
  pair.on = Frame{seq, static_cast<std::int64_t>(seq) * 1000, true, ImageView8(on.view())};
  pair.off = Frame{seq - 1, static_cast<std::int64_t>(seq - 1) * 1000, false, ImageView8(off.view())};
  return pair;
}

inline DotMarker ceiling_marker(int id, double x, double y, double yaw, double z = 2.6) {
  DotMarker marker;
  marker.id = id;
  marker.origin = {x, y, z};
  marker.yaw = yaw;
  return marker;
}

}  // namespace irloc::test
