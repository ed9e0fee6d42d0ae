#pragma once
// Where each pixel's ray meets the ceiling: a per-pixel table built at start-up, so that mapping
// tape pixels to the ceiling plane costs one load per pixel per frame.
//
// The robot is level (robot.dof 3 or 4), so the camera's rays are known in the base frame's axes.
// A ray that rises at least cos(max_ray_angle) toward the ceiling, height h above the camera
// centre, meets it at a point whose base-frame x, y relative to the camera centre are stored as
// PlanePoint: Q23.8 centimetres (kPlaneUnitsPerMetre). On that plane the square is a square.

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/hough_lines.hpp"

namespace irloc::square {

inline constexpr double kPlaneUnitsPerMetre = 100.0;  // plane unit: centimetre
inline constexpr double kPlaneRawPerMetre = 256.0 * kPlaneUnitsPerMetre;

// A plane point in metres.
inline Eigen::Vector2d metres(PlanePoint p) { return {p.x / kPlaneRawPerMetre, p.y / kPlaneRawPerMetre}; }

class CeilingPlaneMap {
 public:
  // base_from_camera: T_B_C. ceiling_above_camera: h in metres (> 0).
  CeilingPlaneMap(const CameraModel& camera, const RigidTransform& base_from_camera, double ceiling_above_camera,
                  double max_ray_angle);

  int width() const { return width_; }
  int height() const { return height_; }
  double ceiling_above_camera() const { return ceiling_above_camera_; }
  // Largest |x|, |y| of any stored point, metres.
  double max_radius() const { return max_radius_; }
  // The finest ceiling footprint of a pixel anywhere, metres: sets the thin-line element size.
  double min_metres_per_pixel() const { return min_metres_per_pixel_; }

  // The smallest pixel rectangle holding every mapped pixel: the rest of a frame can be skipped.
  struct Region {
    int x = 0, y = 0, width = 0, height = 0;
  };
  const Region& mapped_region() const { return mapped_region_; }

  // Ceiling footprint of pixel (x, y), metres per pixel (the larger of the steps to the next pixel
  // right and down); 0 where the table has no point. (x, y) inside the image.
  double metres_per_pixel(int x, int y) const;

  // Points of row y; x is invalid (kNoPoint) where the ray misses the mapped ceiling.
  const PlanePoint* row(int y) const { return points_.data() + static_cast<std::size_t>(y) * width_; }
  static constexpr std::int32_t kNoPoint = INT32_MIN;

 private:
  int width_ = 0;
  int height_ = 0;
  double ceiling_above_camera_ = 0;
  double max_radius_ = 0;
  double min_metres_per_pixel_ = 0;
  Region mapped_region_;
  std::vector<PlanePoint> points_;
};

}  // namespace irloc::square
