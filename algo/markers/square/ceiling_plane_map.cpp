#include "algo/markers/square/ceiling_plane_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace irloc::square {

CeilingPlaneMap::CeilingPlaneMap(const CameraModel& camera, const RigidTransform& base_from_camera,
                                 double ceiling_above_camera, double max_ray_angle)
    : width_(camera.intrinsics().width),
      height_(camera.intrinsics().height),
      ceiling_above_camera_(ceiling_above_camera),
      points_(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_)) {
  const double min_rise = std::cos(max_ray_angle);
  const Eigen::Matrix3d base_from_camera_rotation = base_from_camera.rotation;
  // Metric positions of the previous row, to measure each pixel's footprint.
  std::vector<Eigen::Vector2d> previous_row(static_cast<std::size_t>(width_));
  std::vector<bool> previous_valid(static_cast<std::size_t>(width_), false);
  min_metres_per_pixel_ = std::numeric_limits<double>::infinity();
  int x_min = width_, y_min = height_, x_max = -1, y_max = -1;
  for (int y = 0; y < height_; ++y) {
    bool left_valid = false;
    Eigen::Vector2d left = Eigen::Vector2d::Zero();
    for (int x = 0; x < width_; ++x) {
      PlanePoint& out = points_[static_cast<std::size_t>(y) * width_ + x];
      out = {kNoPoint, kNoPoint};
      Eigen::Vector3d bearing;
      bool valid = camera.unproject(Eigen::Vector2d(x, y), bearing);
      Eigen::Vector2d metric = Eigen::Vector2d::Zero();
      if (valid) {
        const Eigen::Vector3d ray = base_from_camera_rotation * bearing.normalized();
        valid = ray.z() >= min_rise && ray.z() > 0;
        if (valid) metric = ray.head<2>() * (ceiling_above_camera / ray.z());
      }
      if (valid) {
        out = {static_cast<std::int32_t>(std::lround(metric.x() * kPlaneRawPerMetre)),
               static_cast<std::int32_t>(std::lround(metric.y() * kPlaneRawPerMetre))};
        x_min = std::min(x_min, x);
        x_max = std::max(x_max, x);
        y_min = std::min(y_min, y);
        y_max = std::max(y_max, y);
        max_radius_ = std::max({max_radius_, std::abs(metric.x()), std::abs(metric.y())});
        if (left_valid) min_metres_per_pixel_ = std::min(min_metres_per_pixel_, (metric - left).norm());
        if (previous_valid[static_cast<std::size_t>(x)]) {
          min_metres_per_pixel_ = std::min(min_metres_per_pixel_, (metric - previous_row[static_cast<std::size_t>(x)]).norm());
        }
        previous_row[static_cast<std::size_t>(x)] = metric;
      }
      previous_valid[static_cast<std::size_t>(x)] = valid;
      left_valid = valid;
      left = metric;
    }
  }
  if (x_max >= 0) mapped_region_ = {x_min, y_min, x_max - x_min + 1, y_max - y_min + 1};
}

double CeilingPlaneMap::metres_per_pixel(int x, int y) const {
  const int x0 = std::min(x, width_ - 2);
  const int y0 = std::min(y, height_ - 2);
  const PlanePoint p = row(y0)[x0], right = row(y0)[x0 + 1], down = row(y0 + 1)[x0];
  if (p.x == kNoPoint || right.x == kNoPoint || down.x == kNoPoint) return 0;
  const double step_right = std::hypot(double(right.x) - p.x, double(right.y) - p.y);
  const double step_down = std::hypot(double(down.x) - p.x, double(down.y) - p.y);
  return std::max(step_right, step_down) / kPlaneRawPerMetre;
}

}  // namespace irloc::square
