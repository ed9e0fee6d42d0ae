#pragma once
// The corridor of the movable-marker paper (Yang et al., docs/survey.md) as synthetic
// observations: 12 dot markers in two rows 1.8 m apart on a 2.6 m ceiling, installed off their
// drawing by up to 0.25 m and 5 degrees (marker 0, the reference, exactly), seen by a 1280 x 960
// pinhole on a level robot driving between the rows. Each dot's pixel is its true centre
// projected with Gaussian noise; a marker counts as seen when all its dots are in the image.

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/markers/dot/dot_marker_layout.hpp"
#include "algo/source/source_result.hpp"

namespace irloc::test {

inline CameraIntrinsics corridor_camera() {
  CameraIntrinsics camera;
  camera.width = 1280;
  camera.height = 960;
  camera.fx = camera.fy = 800;
  camera.cx = 639.5;
  camera.cy = 479.5;
  return camera;
}

// T_B_C of the `up` preset 0.3 m above the base.
inline RigidTransform corridor_mount() {
  RigidTransform mount;
  mount.rotation << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  mount.translation = {0.05, 0.0, 0.3};
  return mount;
}

inline int corridor_id(int index) { return 1000 + 37 * index; }

// The corridor as drawn: `markers` dot markers in two rows `spacing` apart, `spacing` apart along
// the rows, on the 2.6 m ceiling; marker 0, the reference, fixed.
inline MarkerMap corridor_drawing(int markers, double spacing = 1.8) {
  MarkerMap drawing;
  for (int index = 0; index < markers; ++index) {
    DotMarker drawn;
    drawn.id = corridor_id(index);
    drawn.origin = {spacing * (index % 2), spacing * (index / 2), 2.6};
    drawn.yaw = 0;
    drawn.fixed = index == 0;
    drawing.dot_markers.push_back(drawn);
  }
  return drawing;
}

// The drawing with every other ID of the 4,096 placed on a grid 100 m away: markers no drive sees
// (issue 32's map of every ID).
inline MarkerMap with_every_other_id(const MarkerMap& drawing) {
  MarkerMap map = drawing;
  for (int id = 0; id <= dot::kMaxMarkerId; ++id) {
    if (map.find_dot_marker(id) != nullptr) continue;
    DotMarker far;
    far.id = id;
    far.origin = {100.0 + 2.0 * (id % 64), 2.0 * (id / 64), 2.6};
    map.dot_markers.push_back(far);
  }
  return map;
}

struct Corridor {
  MarkerMap drawing;  // the map as drawn: marker 0 fixed, the others approximate
  MarkerMap truth;    // where the markers really are

  explicit Corridor(unsigned seed, int markers = 12) : drawing(corridor_drawing(markers)), truth(drawing) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> offset(-1.0, 1.0);
    for (DotMarker& installed : truth.dot_markers) {
      if (installed.fixed) continue;
      // Off by up to 0.25 m horizontally, 3 cm in height, 5 degrees.
      const double angle = std::numbers::pi * offset(random), distance = 0.25 * std::abs(offset(random));
      installed.origin += Eigen::Vector3d(distance * std::cos(angle), distance * std::sin(angle), 0.03 * offset(random));
      installed.yaw = 5.0 * std::numbers::pi / 180 * offset(random);
    }
  }
};

// The centroid error of a dot sampled on a pixel grid: a fixed function of where its centre falls
// within a pixel, `amplitude` px at most per axis. A straight drive at a constant heading keeps
// the phase across the motion, so every sighting of a stretch repeats that part of it.
// `axes` scales it per image axis (u, v): (1, 0) keeps the part across a drive along v alone.
inline Eigen::Vector2d pixel_grid_error(const Eigen::Vector2d& pixel, double amplitude,
                                        const Eigen::Vector2d& axes = Eigen::Vector2d::Ones()) {
  return amplitude * axes.cwiseProduct(
                         Eigen::Vector2d(std::sin(2 * std::numbers::pi * pixel.x()), std::sin(2 * std::numbers::pi * pixel.y())));
}

// The dots of every fully visible marker of `markers`, seen from the level robot pose (x, y, yaw):
// fresh Gaussian noise of `pixel_noise` px per frame, plus the pixel grid's error of
// `grid_error` px at most (pixel_grid_error()).
inline PointObservationList observe(const std::vector<DotMarker>& markers, double x, double y, double yaw,
                                    double pixel_noise, std::mt19937& random, double grid_error = 0,
                                    const Eigen::Vector2d& grid_axes = Eigen::Vector2d::Ones()) {
  const CameraModel camera(corridor_camera());
  const RigidTransform world_from_base{rotation_from_rpy(0, 0, yaw), {x, y, 0}};
  const RigidTransform camera_from_world = (world_from_base * corridor_mount()).inverse();
  std::normal_distribution<double> noise(0.0, pixel_noise);
  PointObservationList observations;
  for (const DotMarker& marker : markers) {
    const dot::CellMask cells = dot::cells_from_id(marker.id);
    PointObservationList dots;
    bool visible = true;
    for (int cell = 0; cell < dot::kCellCount && visible; ++cell) {
      if (((cells >> cell) & 1u) == 0) continue;
      const Eigen::Vector3d world = dot::cell_in_world(marker, cell);
      Eigen::Vector2d pixel;
      visible = camera.project(camera_from_world * world, pixel) && pixel.x() > 10 && pixel.y() > 10 &&
                pixel.x() < 1270 && pixel.y() < 950;
      dots.push_back(
          {marker.id, cell, pixel + Eigen::Vector2d(noise(random), noise(random)) + pixel_grid_error(pixel, grid_error, grid_axes), world});
    }
    if (!visible) continue;
    for (const PointObservation& dot : dots) observations.push_back(dot);
  }
  return observations;
}

// One pass along the corridor between the rows, y from -0.6 to y_end (or back), 2 cm per frame,
// weaving 0.3 m across.
struct PassPose {
  double x, y, yaw;
};
inline std::vector<PassPose> corridor_pass(double y_end, bool back) {
  std::vector<PassPose> poses;
  const double y_start = -0.6, step = 0.02;
  const int frames = static_cast<int>((y_end - y_start) / step);
  for (int k = 0; k <= frames; ++k) {
    const double along = back ? y_end - k * step : y_start + k * step;
    const double x = 0.9 + 0.3 * std::sin(along * 1.3);
    poses.push_back({x, along, (back ? -1 : 1) * std::numbers::pi / 2 + 0.2 * std::sin(along * 0.9)});
  }
  return poses;
}

}  // namespace irloc::test
