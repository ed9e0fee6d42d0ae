#pragma once
// OpenCV's projectPoints (plumb_bob) as an independent projection for the oracle tests, and the
// rolling shutter built on it row by row (row v exposed v * line_time after row 0, conventions.md).

#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "algo/geometry/camera_intrinsics.hpp"

namespace irloc::test {

// OpenCV's projection of `world` from the camera pose t_w_c.
inline Eigen::Vector2d opencv_projection(const Eigen::Vector3d& world, const Eigen::Isometry3d& t_w_c,
                                         const CameraIntrinsics& k) {
  const Eigen::Isometry3d t_c_w = t_w_c.inverse();
  const Eigen::Matrix3d r = t_c_w.linear();
  cv::Vec3d rvec;
  cv::Rodrigues(cv::Matx33d(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)), rvec);
  const cv::Vec3d tvec(t_c_w.translation().x(), t_c_w.translation().y(), t_c_w.translation().z());
  const cv::Matx33d camera_matrix(k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1);
  const std::vector<double> distortion(k.distortion.begin(), k.distortion.begin() + 5);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(std::vector<cv::Point3d>{{world.x(), world.y(), world.z()}}, rvec, tvec, camera_matrix, distortion, pixels);
  return {pixels[0].x, pixels[0].y};
}

// The pixel of `world` under a rolling shutter: for each row v, OpenCV's projection from the
// camera pose at v * line_time seconds after row 0 (t_w_c_at(seconds)); the row its projection
// lands in, interpolated between the two rows the projection crosses. NaN when it lands in none.
template <typename PoseAt>
Eigen::Vector2d opencv_rolling_projection(const Eigen::Vector3d& world, const CameraIntrinsics& k, double line_time,
                                          const PoseAt& t_w_c_at) {
  double previous_gap = 0;
  Eigen::Vector2d previous = Eigen::Vector2d::Zero();
  for (int row = 0; row < k.height; ++row) {
    const Eigen::Vector2d pixel = opencv_projection(world, t_w_c_at(row * line_time), k);
    const double gap = pixel.y() - row;
    if (row > 0 && gap <= 0 && previous_gap > 0) return previous + previous_gap / (previous_gap - gap) * (pixel - previous);
    previous_gap = gap;
    previous = pixel;
  }
  return Eigen::Vector2d::Constant(std::nan(""));
}

}  // namespace irloc::test
