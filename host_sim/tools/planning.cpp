#include "host_sim/tools/planning.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "algo/geometry/camera_model.hpp"
#include "io/input_error.hpp"
#include "host_sim/render/ceiling_layout.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/render/noise.hpp"
#include "host_sim/render/radiometry.hpp"
#include "host_sim/scenario/trajectory.hpp"

namespace irloc::sim {
namespace {

Eigen::Isometry3d planar(double x, double y, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation_from_rpy(0, 0, yaw);
  t.translation() = Eigen::Vector3d(x, y, 0);
  return t;
}

bool all_visible(const std::vector<ProjectedPoint>& points) {
  for (const ProjectedPoint& p : points) {
    if (!p.visible) return false;
  }
  return !points.empty();
}

}  // namespace

HeatMap led_ring_brightness(const Scenario& scenario, double half_extent, int cells) {
  const CameraModel camera(scenario.camera.intrinsics);
  const Trajectory trajectory(scenario.trajectory);
  const Eigen::Isometry3d t_w_b = trajectory.t_w_b(0);
  const Eigen::Isometry3d t_w_c = t_w_b * scenario.camera.mount;
  const RingIllumination ring(scenario.ring, t_w_c);
  const Sensor sensor(scenario.camera, scenario.seed);

  HeatMap map;
  map.columns = map.rows = cells;
  const Eigen::Vector3d centre = t_w_c.translation();
  map.x0 = centre.x() - half_extent;
  map.x1 = centre.x() + half_extent;
  map.y0 = centre.y() - half_extent;
  map.y1 = centre.y() + half_extent;
  map.marks.emplace_back(t_w_b.translation().x(), t_w_b.translation().y());
  map.unit = "% full scale";
  map.title = "Retro-reflector brightness on the ceiling";
  const double h = scenario.room.ceiling_height;
  double brightest = 0;
  for (int r = 0; r < cells; ++r) {
    for (int c = 0; c < cells; ++c) {
      const Eigen::Vector3d point(map.x0 + (c + 0.5) * (map.x1 - map.x0) / cells,
                                  map.y0 + (r + 0.5) * (map.y1 - map.y0) / cells, h);
      const bool seen = project_points(camera, t_w_b, scenario.camera.mount, {point}).front().visible;
      double value = std::numeric_limits<double>::quiet_NaN();
      if (seen) {
        const double radiance = ring.retro_radiance(point, Eigen::Vector3d(0, 0, -1), scenario.retro);
        value = 100 * sensor.electrons(radiance) / scenario.camera.full_well;
        brightest = std::max(brightest, value);
      }
      map.values.push_back(value);
    }
  }
  map.low = 0;
  map.high = std::max(brightest, 1e-6);
  return map;
}

namespace {

// The floor the coverage map spans: the room's bounds, else the landmarks' extent and 1 m more;
// cut into cells of about `cell` metres, at most kMaxFloorCells.
HeatMap coverage_floor(const Scenario& scenario, double cell) {
  const MarkerMap& markers = scenario.map;
  HeatMap map;
  if (scenario.room.bounds) {
    const Eigen::Vector4d& b = *scenario.room.bounds;
    map.x0 = b[0]; map.y0 = b[1]; map.x1 = b[2]; map.y1 = b[3];
  } else {
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    const auto extend = [&](const Eigen::Vector3d& p) {
      x0 = std::min(x0, p.x()); y0 = std::min(y0, p.y()); x1 = std::max(x1, p.x()); y1 = std::max(y1, p.y());
    };
    for (const DotMarker& m : markers.dot_markers) extend(m.origin);
    for (const SquareMarker& m : markers.square_markers) for (const auto& c : m.corners) extend(c);
    for (const LedLandmark& m : markers.led_landmarks) extend(m.position);
    if (x0 > x1) throw io::InputError(scenario.name + ": map: coverage needs landmarks or room.bounds");
    map.x0 = x0 - 1; map.y0 = y0 - 1; map.x1 = x1 + 1; map.y1 = y1 + 1;
  }
  const double columns = std::max(1.0, std::round((map.x1 - map.x0) / cell));
  const double rows = std::max(1.0, std::round((map.y1 - map.y0) / cell));
  if (!(columns * rows <= kMaxFloorCells)) {
    char message[240];
    std::snprintf(message, sizeof message,
                  "--cell %g: the floor (%.1f x %.1f m) would be %.0f x %.0f cells, more than %d: use a larger --cell",
                  cell, map.x1 - map.x0, map.y1 - map.y0, columns, rows, kMaxFloorCells);
    throw io::InputError(message);
  }
  map.columns = static_cast<int>(columns);
  map.rows = static_cast<int>(rows);
  return map;
}

// The landmarks whole in view from a base pose: LEDs shining toward the camera, dot markers with
// every dot, squares with every corner.
int landmarks_in_view(const Scenario& scenario, const CameraModel& camera, const Eigen::Isometry3d& t_w_b,
                      const std::vector<std::vector<Eigen::Vector3d>>& dot_sets) {
  const MarkerMap& markers = scenario.map;
  const Eigen::Vector3d camera_centre = (t_w_b * scenario.camera.mount).translation();
  int count = 0;
  for (const LedLandmark& landmark : markers.led_landmarks) {
    if (landmark_intensity(landmark, 1.0, camera_centre) > 0 &&
        project_points(camera, t_w_b, scenario.camera.mount, {landmark.position}).front().visible) {
      ++count;
    }
  }
  for (const auto& dots : dot_sets) count += all_visible(project_points(camera, t_w_b, scenario.camera.mount, dots));
  for (const SquareMarker& square : markers.square_markers) {
    const std::vector<Eigen::Vector3d> corners(square.corners.begin(), square.corners.end());
    count += all_visible(project_points(camera, t_w_b, scenario.camera.mount, corners));
  }
  return count;
}

}  // namespace

HeatMap landmark_coverage(const Scenario& scenario, double cell, int headings) {
  const CameraModel camera(scenario.camera.intrinsics);
  const MarkerMap& markers = scenario.map;
  HeatMap map = coverage_floor(scenario, cell);
  map.discrete = true;
  map.unit = "landmarks";
  for (const LedLandmark& m : markers.led_landmarks) map.marks.emplace_back(m.position.x(), m.position.y());
  for (const DotMarker& m : markers.dot_markers) map.marks.emplace_back(m.origin.x(), m.origin.y());

  std::vector<std::vector<Eigen::Vector3d>> dot_sets;
  for (const DotMarker& m : markers.dot_markers) dot_sets.push_back(CeilingLayout::dot_centres(m));
  int most = 0;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.columns; ++c) {
      const double x = map.x0 + (c + 0.5) * (map.x1 - map.x0) / map.columns;
      const double y = map.y0 + (r + 0.5) * (map.y1 - map.y0) / map.rows;
      int fewest = std::numeric_limits<int>::max();
      for (int k = 0; k < headings; ++k) {
        const Eigen::Isometry3d t_w_b = planar(x, y, 2 * std::numbers::pi * k / headings);
        fewest = std::min(fewest, landmarks_in_view(scenario, camera, t_w_b, dot_sets));
      }
      most = std::max(most, fewest);
      map.values.push_back(fewest);
    }
  }
  map.low = 0;
  map.high = std::max(most, 1);
  return map;
}

double coverage_fraction(const HeatMap& coverage, int k) {
  if (coverage.values.empty()) return 0;
  std::size_t covered = 0;
  for (const double value : coverage.values) covered += value >= k ? 1 : 0;
  return static_cast<double>(covered) / static_cast<double>(coverage.values.size());
}

}  // namespace irloc::sim
