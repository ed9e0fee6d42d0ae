#include "host_sim/render/marker_view.hpp"

#include "host_sim/render/ceiling_layout.hpp"
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
