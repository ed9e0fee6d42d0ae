#pragma once
// A ray-cast renderer of the square tape marker for the square-path tests: an equisolid fisheye
// under a level ceiling, every pixel supersampled 2 x 2 against the tape pattern of
// docs/markers.md (optionally supersampled), with parts of the tape hidden on request (a person in the way). It shares no
// code with the path under test beyond CameraModel::unproject.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "algo/core/image.hpp"
#include "algo/kernels/difference_noise.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/map/marker_map.hpp"

namespace irloc::test {

inline constexpr double kTapeCeilingZ = 2.3;  // 2 m above a camera 0.3 m above the floor

// Equisolid fisheye whose image circle (90 degrees off axis) just fits the height.
inline CameraIntrinsics fisheye(int width, int height) {
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = k.fy = height / (2 * std::sqrt(2.0)) * 1.0;
  k.cx = (width - 1) / 2.0;
  k.cy = (height - 1) / 2.0;
  k.model = LensModel::equisolid;
  return k;
}

// The `up` preset, 0.05 m forward and 0.3 m up.
inline Eigen::Isometry3d up_mount() {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation() = Eigen::Vector3d(0.05, 0, 0.3);
  return mount;
}

// A square of side d centred at (x, y) on the ceiling, c0 -> c1 along the direction yaw.
inline SquareMarker tape_square(double x, double y, double yaw, double side = 2.0) {
  SquareMarker marker;
  marker.name = "hall";
  const Eigen::Matrix3d r = rotation_from_rpy(0, 0, yaw);
  const double h = side / 2;
  const Eigen::Vector3d centre(x, y, kTapeCeilingZ);
  marker.corners = {centre + r * Eigen::Vector3d(-h, -h, 0), centre + r * Eigen::Vector3d(h, -h, 0),
                    centre + r * Eigen::Vector3d(h, h, 0), centre + r * Eigen::Vector3d(-h, h, 0)};
  return marker;
}

// A stretch [from, to] (metres from the side's start corner) of side k that nobody can see.
struct HiddenStretch {
  int side = 0;
  double from = 0, to = 0;
};

// true when the ceiling point (x, y) is visible tape.
inline bool on_tape(const SquareMarker& marker, const Eigen::Vector2d& point, const std::vector<HiddenStretch>& hidden,
                    bool all_dashed = false) {
  const double half = marker.tape_width / 2;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d a = marker.corners[static_cast<std::size_t>(k)].head<2>();
    const Eigen::Vector2d b = marker.corners[static_cast<std::size_t>((k + 1) % 4)].head<2>();
    const double length = (b - a).norm();
    const Eigen::Vector2d u = (b - a) / length;
    const Eigen::Vector2d d = point - a;
    const double s = d.dot(u);
    const double t = u.x() * d.y() - u.y() * d.x();
    if (std::abs(t) > half || s < -half || s > length + half) continue;
    bool hidden_here = false;
    for (const HiddenStretch& h : hidden) hidden_here |= h.side == k && s >= h.from && s <= h.to;
    if (hidden_here) continue;
    const bool corner = s <= half || s >= length - half;
    const bool dashed = k != 0 || all_dashed;
    if (corner || !dashed || std::fmod(s, marker.dash + marker.gap) < marker.dash) return true;
  }
  return false;
}

// Other retro-reflective things on the ceiling (they shine in the LED-on frame like the tape): a
// strip of safety tape (a rectangle) or a round sticker half in shadow (a half disc: the crescent).
struct Clutter {
  enum class Kind { strip, crescent } kind = Kind::strip;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double yaw = 0;       // the strip's length direction; the direction the crescent's lit half faces
  double length = 1.0;  // strip length
  double width = 0.05;  // strip width; the crescent's radius
};

inline bool on_clutter(const Clutter& item, const Eigen::Vector2d& point) {
  const Eigen::Vector2d axis(std::cos(item.yaw), std::sin(item.yaw));
  const Eigen::Vector2d d = point - item.centre;
  const double along = d.dot(axis), across = axis.x() * d.y() - axis.y() * d.x();
  if (item.kind == Clutter::Kind::strip) return std::abs(along) <= item.length / 2 && std::abs(across) <= item.width / 2;
  return d.norm() <= item.width && along >= 0;
}

struct TapeScene {
  CameraIntrinsics camera = fisheye(640, 512);
  Eigen::Isometry3d mount = up_mount();
  SquareMarker marker = tape_square(0, 0, 0);
  double x = 0, y = 0, yaw = 0;  // the robot
  double roll = 0, pitch = 0;    // its tilt (dof 6)
  std::vector<HiddenStretch> hidden;
  std::vector<Clutter> clutter;
  std::vector<SquareMarker> other_squares;  // painted too, not in the map under test
  bool all_dashed = false;  // paint the solid side dashed too
  int tape_level = 180;     // difference of a pixel fully on tape
  int lamp_level = 250;     // a lamp, bright in both frames
  double noise_sigma = 3;   // grey levels, both frames
  unsigned seed = 1;
  int samples = 1;  // rays per pixel along each axis (1: the pixel centre; 2: 2 x 2 supersampling)
  // A rolling shutter: row v seen v * line_time seconds after the pose above (x, y, yaw), the robot
  // driving at `velocity` (m/s, in its heading frame) and turning at yaw_rate (rad/s) meanwhile.
  double line_time = 0;
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  double yaw_rate = 0;

  // T_W_C of the robot's pose, dt seconds later: the heading-frame velocity integrated in closed
  // form along the turn.
  Eigen::Isometry3d world_from_camera_pose(double dt = 0) const {
    const double heading = yaw + yaw_rate * dt;
    // The integral over [0, dt] of the heading's (cos, sin).
    Eigen::Vector2d swept(std::cos(yaw) * dt, std::sin(yaw) * dt);
    if (std::abs(yaw_rate) > 1e-12) {
      swept = Eigen::Vector2d(std::sin(heading) - std::sin(yaw), std::cos(yaw) - std::cos(heading)) / yaw_rate;
    }
    const Eigen::Vector2d moved(velocity.x() * swept.x() - velocity.y() * swept.y(),
                                velocity.x() * swept.y() + velocity.y() * swept.x());
    Eigen::Isometry3d world_from_base = Eigen::Isometry3d::Identity();
    world_from_base.linear() = rotation_from_rpy(roll, pitch, heading);
    world_from_base.translation() = Eigen::Vector3d(x + moved.x(), y + moved.y(), 0);
    return world_from_base * mount;
  }

  // Where the samples x samples sub-pixel rays of every pixel meet the ceiling (NaN: no hit). The
  // costly part of render(); scenes that differ only in what is hidden can share it.
  std::vector<Eigen::Vector2d> ceiling_hits() const {
    const CameraModel model(camera);
    const int rays = samples * samples;
    std::vector<Eigen::Vector2d> hits(static_cast<std::size_t>(camera.width) * camera.height * rays,
                                      Eigen::Vector2d::Constant(std::nan("")));
    for (int v = 0; v < camera.height; ++v) {
      const Eigen::Isometry3d world_from_camera = world_from_camera_pose(v * line_time);
      const Eigen::Vector3d origin = world_from_camera.translation();
      for (int u = 0; u < camera.width; ++u) {
        for (int sub = 0; sub < rays; ++sub) {
          Eigen::Vector3d bearing;
          const Eigen::Vector2d pixel(u - 0.5 + (sub % samples + 0.5) / samples, v - 0.5 + (sub / samples + 0.5) / samples);
          if (!model.unproject(pixel, bearing)) continue;
          const Eigen::Vector3d ray = world_from_camera.linear() * bearing;
          if (ray.z() <= 0.05) continue;
          hits[(static_cast<std::size_t>(v) * camera.width + u) * rays + sub] =
              (origin + ray * ((kTapeCeilingZ - origin.z()) / ray.z())).head<2>();
        }
      }
    }
    return hits;
  }

  // Renders the LED-on and LED-off frames.
  void render(Image8& on, Image8& off) const { render(ceiling_hits(), on, off); }

  // The same from this scene's ceiling_hits().
  void render(const std::vector<Eigen::Vector2d>& hits, Image8& on, Image8& off) const {
    on = Image8(camera.width, camera.height);
    off = Image8(camera.width, camera.height);
    const Eigen::Vector2d lamp(marker.corners[0].x() + 0.6, marker.corners[0].y() + 0.6);  // inside the square
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0, noise_sigma);
    const int rays = samples * samples;
    for (int v = 0; v < camera.height; ++v) {
      for (int u = 0; u < camera.width; ++u) {
        int covered = 0, lamp_covered = 0;
        for (int sub = 0; sub < rays; ++sub) {
          const Eigen::Vector2d& hit = hits[(static_cast<std::size_t>(v) * camera.width + u) * rays + sub];
          if (std::isnan(hit.x())) continue;
          bool lit_here = on_tape(marker, hit, hidden, all_dashed);
          for (const Clutter& item : clutter) lit_here = lit_here || on_clutter(item, hit);
          for (const SquareMarker& other : other_squares) lit_here = lit_here || on_tape(other, hit, {});
          covered += lit_here;
          lamp_covered += (hit - lamp).cwiseAbs().maxCoeff() < 0.3;
        }
        const double background = 20 + lamp_level * lamp_covered / static_cast<double>(rays);
        const double lit = background + tape_level * covered / static_cast<double>(rays);
        on.view().at(u, v) = static_cast<std::uint8_t>(std::clamp(std::lround(lit + noise(rng)), 0L, 255L));
        off.view().at(u, v) = static_cast<std::uint8_t>(std::clamp(std::lround(background + noise(rng)), 0L, 255L));
      }
    }
  }
};

// The pair's noise estimate as the Localizer's shared pass makes it (48 sampled rows, the dot
// config's default threshold_rows), for the detector used on its own.
template <typename View>
DifferenceNoise shared_noise(View on, View off) {
  return DifferenceNoiseEstimator(on.height(), 48).estimate(on, off);
}

}  // namespace irloc::test
