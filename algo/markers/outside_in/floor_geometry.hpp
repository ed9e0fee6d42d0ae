#pragma once
// The fixed camera's pose over the floor from its intrinsics and floor points of known position
// (config `camera.floor_reference`: the corners of a tile, of several tiles, or of any marks on
// the floor z = 0), by planar PnP (algo/geometry/planar_pnp.hpp), and how uncertain that pose is
// given how precisely the points' pixels were measured (the box fit maps that covariance into
// every pose's: BoxFit::camera_sensitivity). Start-up only.
#include <string>
#include <vector>
#include <Eigen/Core>
#include "algo/geometry/camera_intrinsics.hpp"
#include "algo/geometry/rigid_transform.hpp"

namespace irloc::outside_in {

struct FloorReference {
  std::vector<Eigen::Vector2d> world;   // points on the floor, W metres; at least 4, at most kMaxPoints
  std::vector<Eigen::Vector2d> pixels;  // the same points in the image, px, same order
  // px: the standard deviation of one pixel coordinate as measured (a careful click on a zoomed
  // still frame: 0.3; a quick click: 1). Both the check and the covariance use it.
  double pixel_sigma = 0.5;
  static constexpr std::size_t kMaxPoints = 64;
};

struct FloorGeometry {
  bool ok = false;
  std::string error;                  // why not, naming the check that failed (start-up only)
  RigidTransform camera_from_world;   // T_C_W
  double reprojection_rms_px = 0;     // per point (2-D norm)
  // Covariance of T_C_W over the perturbation (exp([w]x) R, t + dt), (w, dt) in C (rad, m):
  // sigma^2 (J^T J)^-1, sigma the larger of pixel_sigma and the residuals' own estimate.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();
};

// Checks, in this order, each failure naming its field: at least 4 points and as many pixels;
// world points at least 5 cm apart and not on one line; pixels inside the image and inside the
// lens model's field of view; a pose found; the camera above the floor; and the pixels'
// reprojection consistent with pixel_sigma: the sum of squared residuals / sigma^2 within the
// 99.9 % quantile of chi-square with 2n - 6 degrees of freedom (for 4 points: RMS <= 1.86 sigma).
FloorGeometry solve_floor_geometry(const CameraIntrinsics& camera, const FloorReference& reference);

}  // namespace irloc::outside_in
