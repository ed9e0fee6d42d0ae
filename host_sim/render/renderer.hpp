#pragma once
// Renders the scene radiance a camera sees: per pixel, a supersampled grid of rays through the
// inverse camera model, intersected with people, walls, LED landmarks and the ceiling; each
// ray's radiance from the model of host_sim/render/radiometry.hpp. Rays are computed once at start-up;
// rendering splits rows over threads and gives the same result for any split.

#include <functional>
#include <limits>
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/render/ceiling_layout.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "host_sim/scenario/trajectory.hpp"

namespace irloc::sim {

class Renderer {
 public:
  // Keeps references to nothing: the scenario and camera are copied.
  Renderer(const Scenario& scenario, const CameraModel& camera);

  int width() const { return width_; }
  int height() const { return height_; }

  // Camera pose in the world at time t (seconds from the start).
  Eigen::Isometry3d t_w_c(double t) const;
  const Trajectory& trajectory() const { return trajectory_; }
  const CameraModel& camera() const { return camera_; }

  // Mean radiance (W sr^-1 m^-2) of every pixel, row-major, for an exposure centred on time t
  // with the robot's LEDs on or off. `radiance` holds width * height values. With a rolling
  // shutter (camera.line_time_ns) row y is rendered exactly from the scene at t + y * line_time:
  // t is the middle of the top row's exposure, as a frame's t_ns (conventions.md).
  void render(double t, bool led_on, std::span<float> radiance) const;

 private:
  struct Instant;
  struct PixelCache;
  // The scene at the motion-blur samples of an exposure centred on t.
  std::vector<Instant> instants(double t, bool led_on) const;
  double exposure_sample_time(double t, int sample) const;
  float pixel_radiance(const Instant& instant, int x, int y) const;
  // true when every ray of the pixel provably sees the same bare ceiling, so its centre ray
  // alone gives the pixel's value (no edge inside the pixel to anti-alias).
  bool uniform_ceiling(const Instant& instant, const Eigen::Vector3d& centre, double spread) const;
  enum class Surface { none, ceiling, wall, person };
  struct RayHit {
    Surface surface = Surface::none;
    double t = std::numeric_limits<double>::infinity();  // along the ray's unit direction, m
    Eigen::Vector3d wall_normal = Eigen::Vector3d::UnitZ();  // a wall's, or the floor's
    std::size_t person = 0;                                // which person
  };
  RayHit nearest_surface(const Instant& instant, const Eigen::Vector3d& direction) const;
  double ray_radiance(const Instant& instant, const Eigen::Vector3d& direction, PixelCache& cache) const;

  Scenario scenario_;
  CameraModel camera_;
  Trajectory trajectory_;
  CeilingLayout ceiling_;
  int width_, height_;
  int samples_per_pixel_;
  // Sub-pixel bearings in the camera frame, samples_per_pixel_ per pixel; NaN x marks a ray
  // outside the lens model's valid region.
  std::vector<Eigen::Vector3f> bearings_;
  // Per pixel: the ray through its centre, and the largest angle (radians) between it and the
  // pixel's sub-pixel rays; negative when some sub-pixel ray is outside the lens's valid region.
  std::vector<Eigen::Vector3f> centres_;
  std::vector<float> spreads_;
};

// Runs body(row) for rows [0, rows) on every hardware thread.
void for_each_row(int rows, const std::function<void(int)>& body);

}  // namespace irloc::sim
