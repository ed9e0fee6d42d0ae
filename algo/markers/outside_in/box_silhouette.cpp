#include "algo/markers/outside_in/box_silhouette.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <Eigen/Cholesky>

namespace irloc::outside_in {
namespace {

using Residuals = Eigen::Matrix<double, 10, 1>;
constexpr double kResidualFloorPx = 0.25;  // the quantization of a pixel mask's moments
constexpr double kChoiceFloorPx = 0.5;     // see fit_box
constexpr double kPriorCap = 4;            // (2 sigma)^2, see fit_box
constexpr double kAmbiguousCost = 10;      // cost / s^2 within which another minimum makes the heading ambiguous
constexpr int kIterations = 15;

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Convex hull of up to 8 points, counter-clockwise in (x, y) (monotone chain); returns the count.
int convex_hull(std::array<Eigen::Vector2d, 8>& points, std::array<Eigen::Vector2d, 17>& hull) {
  std::sort(points.begin(), points.end(),
            [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  int k = 0;
  for (int i = 0; i < 8; ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (int i = 6, lower = k + 1; i >= 0; --i) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  return k - 1;
}

// How far inside the hull's extreme vertex `at` along `axis` (0: x, 1: y) the mask's extent
// ends: the 3 x 3 opening keeps a corner only where three pixel centres fit across it, so a
// wedge whose width grows by w px per px of depth loses its tip to the depth 2 / w (1 px for a
// right angle pointing along the axis, none for an edge along the other axis), at most 3 px.
double opened_tip_depth(const std::array<Eigen::Vector2d, 17>& hull, int count, int at, int axis) {
  constexpr double kAcross = 2, kMaxDepth = 3;
  const Eigen::Vector2d& tip = hull[at];
  const Eigen::Vector2d a = hull[(at + 1) % count] - tip, b = hull[(at + count - 1) % count] - tip;
  const int other = 1 - axis;
  // Width per depth: |a_other / a_axis - b_other / b_axis|, without dividing by a zero depth.
  const double depth_a = std::abs(a(axis)), depth_b = std::abs(b(axis));
  const double spread = std::abs(a(other) * depth_b - b(other) * depth_a);
  if (spread <= kAcross / kMaxDepth * depth_a * depth_b) return kMaxDepth;
  return kAcross * depth_a * depth_b / spread;
}

bool residuals(const BoxSilhouette& box, const Silhouette& observed, const FloorPose& pose, Residuals& r,
               Silhouette* fitted) {
  Silhouette model;
  if (!box.project(pose, model) || model.area < 1) return false;
  const double spread = std::sqrt(std::max(0.5 * (model.mxx + model.myy), 1e-6));
  r << observed.cx - model.cx, observed.cy - model.cy, (observed.mxx - model.mxx) / (2 * spread),
      (observed.myy - model.myy) / (2 * spread), (observed.mxy - model.mxy) / (2 * spread),
      std::sqrt(observed.area) - std::sqrt(model.area), kExtentResidualWeight * (observed.x_min_exact - model.x_min_exact),
      kExtentResidualWeight * (observed.x_max_exact - model.x_max_exact),
      kExtentResidualWeight * (observed.y_min_exact - model.y_min_exact),
      kExtentResidualWeight * (observed.y_max_exact - model.y_max_exact);
  if (fitted) *fitted = model;
  return true;
}

// A local minimum of the residuals' squared norm: Levenberg-Marquardt from one pose.
struct Minimum {
  FloorPose pose;
  double cost = std::numeric_limits<double>::infinity();
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();  // J^T J at the minimum
};

// The residuals' Jacobian in (x, y, yaw) by forward differences from r, the residuals at pose.
bool pose_jacobian(const BoxSilhouette& box, const Silhouette& observed, const FloorPose& pose, const Residuals& r,
                   Eigen::Matrix<double, 10, 3>& jacobian) {
  for (int p = 0; p < 3; ++p) {
    const double step = 1e-5;
    FloorPose moved = pose;
    (p == 0 ? moved.x : p == 1 ? moved.y : moved.yaw) += step;
    Residuals moved_r;
    if (!residuals(box, observed, moved, moved_r, nullptr)) return false;
    jacobian.col(p) = (moved_r - r) / step;
  }
  return true;
}

Minimum descend(const BoxSilhouette& box, const Silhouette& observed, FloorPose pose) {
  Minimum minimum;
  Residuals r;
  if (!residuals(box, observed, pose, r, nullptr)) return minimum;
  double cost = r.squaredNorm();
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 10, 3> jacobian;
  // A rejected step leaves the pose, and so the Jacobian, as they were: it is made again only
  // after an accepted one.
  bool linearized = false;
  double damping = 1e-3;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    if (!linearized) {
      if (!pose_jacobian(box, observed, pose, r, jacobian)) break;
      normal = jacobian.transpose() * jacobian;
      linearized = true;
    }
    Eigen::Matrix3d damped = normal;
    damped.diagonal() *= 1 + damping;
    const Eigen::Vector3d delta = damped.ldlt().solve(-(jacobian.transpose() * r));
    const FloorPose next{pose.x + delta(0), pose.y + delta(1), pose.yaw + delta(2)};
    Residuals next_r;
    if (residuals(box, observed, next, next_r, nullptr) && next_r.squaredNorm() < cost) {
      pose = next;
      r = next_r;
      linearized = false;
      const double previous = cost;
      cost = r.squaredNorm();
      damping = std::max(damping * 0.3, 1e-6);
      if (previous - cost < 1e-10 * (1 + previous)) break;
    } else {
      damping *= 10;
      if (damping > 1e6) break;
    }
  }
  minimum.pose = pose;
  minimum.cost = cost;
  minimum.normal = normal;
  return minimum;
}

// d pose / d camera error at a minimum: the residuals' Jacobian in the camera pose (central
// differences over the perturbation of T_C_W), mapped through the pose's normal equations.
Eigen::Matrix<double, 3, 6> camera_sensitivity(const BoxSilhouette& box, const Silhouette& observed, const FloorPose& pose,
                                               const Eigen::Matrix3d& normal, const Eigen::Matrix<double, 10, 3>& jacobian) {
  Eigen::Matrix<double, 10, 6> by_camera;
  constexpr double kStep = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Residuals sides[2];
    for (int side = 0; side < 2; ++side) {
      const double step = side == 0 ? kStep : -kStep;
      RigidTransform perturbed = box.camera_from_world();
      if (k < 3) perturbed.rotation = Eigen::AngleAxisd(step, Eigen::Vector3d::Unit(k)) * perturbed.rotation;
      else perturbed.translation(k - 3) += step;
      const BoxSilhouette moved(box.camera(), perturbed, box.body());
      if (!residuals(moved, observed, pose, sides[side], nullptr)) return Eigen::Matrix<double, 3, 6>::Zero();
    }
    by_camera.col(k) = (sides[0] - sides[1]) / (2 * kStep);
  }
  return -normal.ldlt().solve(jacobian.transpose() * by_camera);
}

}  // namespace

Silhouette silhouette_of(const Blob& blob) {
  Silhouette s;
  s.area = blob.area;
  s.cx = blob.centroid_x();
  s.cy = blob.centroid_y();
  s.mxx = blob.mu_xx();
  s.myy = blob.mu_yy();
  s.mxy = blob.mu_xy();
  s.x_min = blob.x_min;
  s.y_min = blob.y_min;
  s.x_max = blob.x_max;
  s.y_max = blob.y_max;
  // A pixel's centre is inside the region; the region's edge is half a pixel further out.
  s.x_min_exact = blob.x_min - 0.5;
  s.x_max_exact = blob.x_max + 0.5;
  s.y_min_exact = blob.y_min - 0.5;
  s.y_max_exact = blob.y_max + 0.5;
  return s;
}

BoxSilhouette::BoxSilhouette(const CameraModel& camera, const RigidTransform& camera_from_world, const BoxBody& body)
    : camera_(camera), camera_from_world_(camera_from_world), world_from_camera_(camera_from_world.inverse()), body_(body) {}

bool BoxSilhouette::project(const FloorPose& pose, Silhouette& s) const {
  const double c = std::cos(pose.yaw), si = std::sin(pose.yaw);
  std::array<Eigen::Vector2d, 8> corners;
  int n = 0;
  for (int sx = -1; sx <= 1; sx += 2)
    for (int sy = -1; sy <= 1; sy += 2) {
      const double bx = 0.5 * sx * body_.length, by = 0.5 * sy * body_.width;
      const Eigen::Vector2d floor(pose.x + c * bx - si * by, pose.y + si * bx + c * by);
      for (double z : {0.0, body_.height}) {
        const Eigen::Vector3d point_c = camera_from_world_ * Eigen::Vector3d(floor.x(), floor.y(), z);
        if (point_c.z() <= 0 || !camera_.project(point_c, corners[n])) return false;
        ++n;
      }
    }
  std::array<Eigen::Vector2d, 17> hull;
  const int count = convex_hull(corners, hull);
  double a = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d& p = hull[i];
    const Eigen::Vector2d& q = hull[(i + 1) % count];
    const double cr = p.x() * q.y() - q.x() * p.y();
    a += cr;
    sx += (p.x() + q.x()) * cr;
    sy += (p.y() + q.y()) * cr;
    sxx += (p.x() * p.x() + p.x() * q.x() + q.x() * q.x()) * cr;
    syy += (p.y() * p.y() + p.y() * q.y() + q.y() * q.y()) * cr;
    sxy += (p.x() * q.y() + 2 * p.x() * p.y() + 2 * q.x() * q.y() + q.x() * p.y()) * cr;
  }
  a *= 0.5;
  if (std::abs(a) < 1e-9) return false;
  s.area = std::abs(a);
  s.cx = sx / (6 * a);
  s.cy = sy / (6 * a);
  s.mxx = sxx / (12 * a) - s.cx * s.cx;
  s.myy = syy / (12 * a) - s.cy * s.cy;
  s.mxy = sxy / (24 * a) - s.cx * s.cy;
  int x_min_at = 0, x_max_at = 0, y_min_at = 0, y_max_at = 0;
  for (int i = 1; i < count; ++i) {
    if (hull[i].x() < hull[x_min_at].x()) x_min_at = i;
    if (hull[i].x() > hull[x_max_at].x()) x_max_at = i;
    if (hull[i].y() < hull[y_min_at].y()) y_min_at = i;
    if (hull[i].y() > hull[y_max_at].y()) y_max_at = i;
  }
  s.x_min_exact = hull[x_min_at].x() + opened_tip_depth(hull, count, x_min_at, 0);
  s.x_max_exact = hull[x_max_at].x() - opened_tip_depth(hull, count, x_max_at, 0);
  s.y_min_exact = hull[y_min_at].y() + opened_tip_depth(hull, count, y_min_at, 1);
  s.y_max_exact = hull[y_max_at].y() - opened_tip_depth(hull, count, y_max_at, 1);
  const double x_min = s.x_min_exact, x_max = s.x_max_exact, y_min = s.y_min_exact, y_max = s.y_max_exact;
  s.x_min = static_cast<int>(std::lround(x_min));
  s.x_max = static_cast<int>(std::lround(x_max));
  s.y_min = static_cast<int>(std::lround(y_min));
  s.y_max = static_cast<int>(std::lround(y_max));
  return true;
}

bool BoxSilhouette::floor_point_below(const Eigen::Vector2d& pixel, Eigen::Vector2d& floor) const {
  Eigen::Vector3d bearing;
  if (!camera_.unproject(pixel, bearing)) return false;
  const Eigen::Vector3d direction = world_from_camera_.rotation * bearing;
  const Eigen::Vector3d origin = world_from_camera_.translation;
  if (std::abs(direction.z()) < 1e-9) return false;
  const double t = (0.5 * body_.height - origin.z()) / direction.z();
  if (t <= 0) return false;
  floor = (origin + t * direction).head<2>();
  return true;
}

BoxFit fit_box(const BoxSilhouette& box, const Silhouette& observed, const HeadingPrior& prior) {
  BoxFit best;
  Eigen::Vector2d start;
  if (!box.floor_point_below({observed.cx, observed.cy}, start)) return best;
  const double period = box.body().symmetry_turn();
  // Starting headings across the symmetry turn, and the prior's: near the line of sight the
  // mirror-image minimum is close to the true one, and each needs a start in its own basin.
  constexpr int kHeadingStarts = 8;
  const int starts = prior.sigma > 0 ? kHeadingStarts + 1 : kHeadingStarts;
  std::array<Minimum, kHeadingStarts + 1> minima;
  double least_cost = std::numeric_limits<double>::infinity();
  for (int k = 0; k < starts; ++k) {
    const double yaw = k < kHeadingStarts ? k * period / kHeadingStarts : prior.yaw;
    minima[k] = descend(box, observed, {start.x(), start.y(), yaw});
    least_cost = std::min(least_cost, minima[k].cost);
  }
  if (!std::isfinite(least_cost)) return best;
  // The moments' systematic error (mask edges, shadow, noise) is about kChoiceFloorPx: minima
  // whose costs differ by less than that are told apart by the prior.
  const double sigma2 = std::max(least_cost / (10 - 3), kChoiceFloorPx * kChoiceFloorPx);
  const Minimum* chosen = nullptr;
  double best_choice = std::numeric_limits<double>::infinity();
  for (int k = 0; k < starts; ++k) {
    // The box is the same turned by its symmetry turn: the prior's distance is modulo that.
    const double turn = prior.sigma > 0 ? std::remainder(minima[k].pose.yaw - prior.yaw, period) / prior.sigma : 0;
    // Capped: a minimum far from the prior that the data clearly prefer still wins (the prior
    // is wrong after a turn it mistook for its mirror image).
    const double choice = minima[k].cost / sigma2 + std::min(turn * turn, kPriorCap);
    if (choice < best_choice) {
      best_choice = choice;
      chosen = &minima[k];
    }
  }
  // Minima that the data barely tell from the chosen one: far away, or seen nearly end-on, the
  // box and its mirror image (end-on, both can lie 20 degrees off on either side of the truth).
  double spread = 0;
  for (int k = 0; k < starts; ++k)
    if (minima[k].cost / sigma2 <= chosen->cost / sigma2 + kAmbiguousCost)
      spread = std::max(spread, std::abs(std::remainder(minima[k].pose.yaw - chosen->pose.yaw, period)));
  best.heading_spread = spread;
  best.pose = chosen->pose;
  Residuals r;
  residuals(box, observed, best.pose, r, &best.fitted);
  best.pose.yaw = box.body().folded(best.pose.yaw);
  best.residual_rms_px = std::sqrt(chosen->cost / 10);
  best.residual_norm_px = std::sqrt(chosen->cost);
  best.area_ratio = observed.area / best.fitted.area;
  Eigen::LDLT<Eigen::Matrix3d> ldlt(chosen->normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return best;
  const Eigen::Matrix3d inverse_normal = ldlt.solve(Eigen::Matrix3d::Identity());
  best.covariance = std::max(chosen->cost / (10 - 3), kResidualFloorPx * kResidualFloorPx) * inverse_normal;
  best.per_px_covariance = inverse_normal;
  best.heading_per_px = std::sqrt(std::max(inverse_normal(2, 2), 0.0));
  Eigen::Matrix<double, 10, 3> jacobian;
  if (pose_jacobian(box, observed, chosen->pose, r, jacobian))
    best.camera_sensitivity = camera_sensitivity(box, observed, chosen->pose, jacobian.transpose() * jacobian, jacobian);
  best.ok = best.covariance.allFinite() && best.camera_sensitivity.allFinite();
  return best;
}

}  // namespace irloc::outside_in
