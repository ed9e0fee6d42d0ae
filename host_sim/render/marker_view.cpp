#include "host_sim/render/marker_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "host_sim/render/ceiling_layout.hpp"
#include "host_sim/render/cylinder_hit.hpp"
#include "host_sim/render/radiometry.hpp"

namespace irloc::sim {

std::vector<ProjectedPoint> project_points(const CameraModel& camera, const Eigen::Isometry3d& t_w_b,
                                           const Eigen::Isometry3d& t_b_c, const std::vector<Eigen::Vector3d>& points) {
  const Eigen::Isometry3d t_c_w = (t_w_b * t_b_c).inverse();
  const CameraIntrinsics& k = camera.intrinsics();
  std::vector<ProjectedPoint> result;
  for (const Eigen::Vector3d& point : points) {
    ProjectedPoint projected;
    projected.visible = camera.project(t_c_w * point, projected.pixel) && projected.pixel.x() >= -0.5 &&
                        projected.pixel.y() >= -0.5 && projected.pixel.x() <= k.width - 0.5 &&
                        projected.pixel.y() <= k.height - 0.5;
    result.push_back(projected);
  }
  return result;
}

std::set<int> visible_dot_markers(const CameraModel& camera, const Eigen::Isometry3d& t_w_b,
                                  const Eigen::Isometry3d& t_b_c, const MarkerMap& map) {
  std::set<int> ids;
  for (const DotMarker& marker : map.dot_markers) {
    bool all = true;
    for (const ProjectedPoint& p : project_points(camera, t_w_b, t_b_c, CeilingLayout::dot_centres(marker))) {
      all = all && p.visible;
    }
    if (all) ids.insert(marker.id);
  }
  return ids;
}

namespace {

constexpr double kOutlineStep = 0.05;  // metres between the points checked along the tape's outline

// Points along the outer edge of a square's tape, corner patches included (the tape is centred on
// the sides c_i -> c_i+1).
std::vector<Eigen::Vector3d> tape_outline(const SquareMarker& marker) {
  std::array<Eigen::Vector3d, 4> outer;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d& corner = marker.corners[i];
    const Eigen::Vector3d away = (corner - marker.corners[(i + 1) % 4]).normalized() + (corner - marker.corners[(i + 3) % 4]).normalized();
    outer[i] = corner + marker.tape_width / 2 * away;
  }
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector3d& from = outer[i];
    const Eigen::Vector3d& to = outer[(i + 1) % 4];
    const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / kOutlineStep)));
    for (int k = 0; k < steps; ++k) points.push_back(from + (to - from) * (static_cast<double>(k) / steps));
  }
  return points;
}

}  // namespace

bool square_wholly_in_view(const CameraModel& camera, const Eigen::Isometry3d& t_w_b, const Eigen::Isometry3d& t_b_c,
                           const SquareMarker& marker) {
  for (const ProjectedPoint& p : project_points(camera, t_w_b, t_b_c, tape_outline(marker))) {
    if (!p.visible) return false;
  }
  return true;
}

double most_hidden_side_fraction(const Eigen::Vector3d& camera_centre, const SquareMarker& marker,
                                 const std::vector<Occluder>& people, const std::vector<Eigen::Vector2d>& positions) {
  constexpr int kPointsPerSide = 100;
  double most = 0;
  for (std::size_t side = 0; side < 4; ++side) {
    const Eigen::Vector3d& from = marker.corners[side];
    const Eigen::Vector3d& to = marker.corners[(side + 1) % 4];
    int hidden = 0;
    for (int k = 0; k < kPointsPerSide; ++k) {
      const Eigen::Vector3d to_point = from + (to - from) * ((k + 0.5) / kPointsPerSide) - camera_centre;
      for (std::size_t i = 0; i < people.size(); ++i) {
        if (hit_cylinder(camera_centre, to_point, positions[i], people[i].radius, people[i].height) < 1) {
          ++hidden;
          break;
        }
      }
    }
    most = std::max(most, static_cast<double>(hidden) / kPointsPerSide);
  }
  return most;
}

int visible_led_landmarks(const CameraModel& camera, const Eigen::Isometry3d& t_w_b, const Eigen::Isometry3d& t_b_c,
                          const MarkerMap& map) {
  const Eigen::Vector3d camera_centre = (t_w_b * t_b_c).translation();
  int count = 0;
  for (const LedLandmark& landmark : map.led_landmarks) {
    if (landmark_intensity(landmark, 1.0, camera_centre) > 0 &&
        project_points(camera, t_w_b, t_b_c, {landmark.position}).front().visible) {
      ++count;
    }
  }
  return count;
}

}  // namespace irloc::sim
