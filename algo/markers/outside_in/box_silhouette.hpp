#pragma once
// The robot as a box on the floor and its silhouette in a fixed camera: the convex hull of its
// eight projected corners, summarized by the area, centroid and central second moments that the
// blob labeller measures of a foreground blob. Fitting the box's floor pose (x, y, yaw) to a
// blob's moments puts the pose at the centre of the footprint, not at the blob's centroid (which
// an oblique camera shifts toward the box's top).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <Eigen/Core>
#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/rigid_transform.hpp"
#include "algo/kernels/blob.hpp"

namespace irloc::outside_in {

struct BoxBody {
  double length = 0.60;  // along the robot's x (forward), m
  double width = 0.40;   // along y, m
  double height = 0.35;  // m; B is the centre of the footprint, on the floor
  // The turn that maps the box onto itself: a half turn, a quarter turn for a square footprint
  // (within 2 %), whose outline then tells its heading only modulo 90 degrees.
  double symmetry_turn() const {
    return std::abs(length - width) <= 0.02 * std::max(length, width) ? std::numbers::pi / 2 : std::numbers::pi;
  }
  // yaw in [0, symmetry_turn()): the headings the box looks the same at, as one.
  double folded(double yaw) const {
    const double period = symmetry_turn();
    yaw = std::fmod(yaw, period);
    return yaw < 0 ? yaw + period : yaw;
  }
};

struct FloorPose {
  double x = 0, y = 0;  // W, m
  double yaw = 0;       // heading of the robot's x axis, rad
};

// Area (px^2), centroid (px) and central second moments (px^2) of a region of the image.
struct Silhouette {
  double area = 0;
  double cx = 0, cy = 0;
  double mxx = 0, myy = 0, mxy = 0;
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;  // bounding box, px (rounded)
  double x_min_exact = 0, y_min_exact = 0, x_max_exact = 0, y_max_exact = 0;  // its outer edges, px
};

// A blob's silhouette (geometric moments: a 0/255 mask labelled with its own values).
Silhouette silhouette_of(const Blob& blob);

class BoxSilhouette {
 public:
  BoxSilhouette(const CameraModel& camera, const RigidTransform& camera_from_world, const BoxBody& body);
  // The silhouette of the box at pose; false when a corner is behind the camera or fails to project.
  bool project(const FloorPose& pose, Silhouette& silhouette) const;
  // The floor point whose vertical box has its silhouette centroid near the pixel (the ray
  // through it meets the plane at half the box's height): a starting point for fit().
  bool floor_point_below(const Eigen::Vector2d& pixel, Eigen::Vector2d& floor) const;
  const BoxBody& body() const { return body_; }
  const CameraModel& camera() const { return camera_; }
  const RigidTransform& camera_from_world() const { return camera_from_world_; }

 private:
  const CameraModel& camera_;
  RigidTransform camera_from_world_;
  RigidTransform world_from_camera_;
  BoxBody body_;
};

// The weight of the bounding box's edges among the fit's residuals (fit_box): one pixel's edges,
// where the moments are all of them.
constexpr double kExtentResidualWeight = 0.5;

struct BoxFit {
  bool ok = false;
  FloorPose pose;                  // yaw in [0, body.symmetry_turn()): the box looks the same turned by it
  double residual_rms_px = 0;      // of the moment residuals (px-like units, see .cpp)
  double residual_norm_px = 0;     // their norm: what of the blob the box leaves unexplained
  double area_ratio = 0;           // observed area / fitted silhouette area
  // rad: how far (modulo the symmetry turn) the headings of the minima the data barely tell
  // apart (cost / s^2 within 10 of the chosen one's) lie from it; 0 when it alone fits.
  double heading_spread = 0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of (x, y, yaw), m^2, rad^2
  // rad per px: how far a systematic error of the residuals (norm 1 px, in the worst direction)
  // moves the heading, sqrt((J^T J)^-1)_yaw. The mask is such an error (the opening rounds the
  // silhouette's corners, about a pixel off its edges), which the residual RMS does not show: a
  // nearly square box (0.40 x 0.34 m) standing nearly broadside fitted 14 degrees off at 0.3 px.
  double heading_per_px = 0;
  // (J^T J)^-1: the covariance of (x, y, yaw) per px^2 of a systematic error of the residuals
  // spread over every direction (heading_per_px^2 is its yaw part).
  Eigen::Matrix3d per_px_covariance = Eigen::Matrix3d::Zero();
  // How the pose moves per unit error of the camera pose the box was projected with (the
  // perturbation (exp([w]x) R, t + dt) of T_C_W, (w, dt) in C; floor_geometry.hpp), the observed
  // silhouette held fixed: -(Jp^T Jp)^-1 Jp^T Jc at the fit (the implicit function theorem),
  // Jc by central differences. The floor reference's covariance maps through it.
  Eigen::Matrix<double, 3, 6> camera_sensitivity = Eigen::Matrix<double, 3, 6>::Zero();
  Silhouette fitted;
};

// The heading a track expects (yaw, modulo the box's symmetry turn) and how far from it the
// robot may have turned. Far away, a box turned by +a and by -a from the line of sight casts
// nearly mirror-image silhouettes: two minima of almost equal cost, which the expectation tells
// apart.
struct HeadingPrior {
  double yaw = 0;     // rad
  double sigma = 0;   // rad; 0: no prior
};

// Levenberg-Marquardt over (x, y, yaw) from eight starting headings across the symmetry turn
// (and the prior's), residuals: centroid (px), the change of the silhouette's spread
// d(mu)/(2 sigma) (px), of sqrt(area) (px), and of the four edges of the bounding box (px, half
// weight). Of the minima found, the one of least cost / s^2 + min(((yaw - prior) / sigma)^2, 4)
// wins, s the residual RMS of the best minimum (at least 0.5 px); the prior only chooses, it does
// not enter the pose or its covariance. Bounded work.
BoxFit fit_box(const BoxSilhouette& box, const Silhouette& observed, const HeadingPrior& prior = {});

}  // namespace irloc::outside_in
