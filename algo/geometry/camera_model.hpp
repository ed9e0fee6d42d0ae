#pragma once
// Projection and unprojection of the three lens models of docs/formats.md, with Jacobians.
//
// Camera frame: OpenCV (x right, y down, z forward). Pixels: u right, v down, (0, 0) is the
// centre of the top-left pixel (the same convention as OpenCV's projectPoints).
// No heap, fixed-size Eigen types; construct at start-up, call per frame.
//
// Valid region of each model (project and unproject return false outside it):
// - plumb_bob: points with z > 0 whose undistorted normalized radius r = |(x/z, y/z)| is below
//   r_max, the first radius where the radial map r -> r (1 + k1 r^2 + k2 r^4 + k3 r^6) stops
//   increasing (unbounded when it never does). Beyond r_max the polynomial folds back and one
//   pixel would stand for two directions.
// - equidistant: rays at angle theta from the optical axis below theta_max, the first angle where
//   theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6 + k4 theta^8) stops increasing, and
//   at most pi (so rays with z <= 0 are valid when the lens sees beyond 90 degrees), and not
//   within 1e-12 rad of the backward axis, where the azimuth is lost in rounding.
// - equisolid: theta < pi, and not within 1e-12 rad of the backward axis.
// The region is a property of the lens model, not of the sensor: a valid pixel may lie outside
// the image (see in_image).

#include <Eigen/Core>

#include "algo/geometry/camera_intrinsics.hpp"

namespace irloc {

class CameraModel {
 public:
  // Precondition: fx, fy > 0 (the calibration loader checks it).
  explicit CameraModel(const CameraIntrinsics& intrinsics);

  const CameraIntrinsics& intrinsics() const { return intrinsics_; }

  // Pixel of a point given in camera coordinates. false when the point is outside the valid
  // region above (pixel is then left unspecified).
  bool project(const Eigen::Vector3d& point_c, Eigen::Vector2d& pixel) const;
  // The same, with the 2x3 Jacobian d pixel / d point_c.
  bool project(const Eigen::Vector3d& point_c, Eigen::Vector2d& pixel,
               Eigen::Matrix<double, 2, 3>& d_pixel_d_point) const;

  // Unit bearing vector, in camera coordinates, of a pixel; false outside the valid region.
  bool unproject(const Eigen::Vector2d& pixel, Eigen::Vector3d& bearing) const;

  // Largest valid angle between a ray and the optical axis, radians (pi/2 for an unbounded
  // plumb_bob).
  double max_field_angle() const { return max_field_angle_; }

  // true when the pixel lies on the sensor: u in [-0.5, width - 0.5], v in [-0.5, height - 0.5].
  bool in_image(const Eigen::Vector2d& pixel) const;

 private:
  // Normalized (distorted) image coordinates m of a point and their Jacobian d m / d point.
  bool project_normalized(const Eigen::Vector3d& point_c, Eigen::Vector2d& m,
                          Eigen::Matrix<double, 2, 3>* d_m_d_point) const;
  bool project_pinhole(const Eigen::Vector3d& point_c, Eigen::Vector2d& m,
                       Eigen::Matrix<double, 2, 3>* d_m_d_point) const;
  bool project_radial(const Eigen::Vector3d& point_c, Eigen::Vector2d& m,
                      Eigen::Matrix<double, 2, 3>* d_m_d_point) const;
  bool unproject_pinhole(const Eigen::Vector2d& m, Eigen::Vector3d& bearing) const;
  bool unproject_radial(const Eigen::Vector2d& m, Eigen::Vector3d& bearing) const;

  // plumb_bob: distorted normalized point of an undistorted one, and its 2x2 Jacobian.
  Eigen::Vector2d distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* d_distorted_d_xy) const;
  // Radial lens maps: radius (plumb_bob, of r) or field angle (fisheye models, of theta) to
  // distorted normalized radius, and its derivative.
  double radial_map(double radius_or_angle, double* derivative) const;

  CameraIntrinsics intrinsics_;
  double max_field_angle_ = 0;
  double max_radius_ = 0;            // plumb_bob: r_max (infinity when unbounded)
  double max_distorted_radius_ = 0;  // image of r_max or theta_max under radial_map
};

}  // namespace irloc
