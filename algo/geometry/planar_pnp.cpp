#include "algo/geometry/planar_pnp.hpp"

#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "algo/geometry/homography.hpp"
#include "algo/geometry/rotation_vector.hpp"

namespace irloc {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// IPPE: the two rotations of the plane that agree with the homography's first-order view at the
// plane's origin. p: the origin's normalized image point; jacobian: d image / d plane there.
// With Rv the rotation taking the optical axis onto the ray through p, the plane seen from the
// rotated camera (looking straight at the origin) has the upper-left 2x2 block of its rotation
// equal to the rotated Jacobian up to scale; the block's largest singular value is 1, and the
// third row follows from the columns' unit length and orthogonality, up to one sign.
std::array<Eigen::Matrix3d, 2> ippe_rotations(const Eigen::Vector2d& p, const Eigen::Matrix2d& jacobian) {
  const Eigen::Vector3d ray = Eigen::Vector3d(p.x(), p.y(), 1);
  const Eigen::Vector3d v = ray.normalized();
  Eigen::Matrix3d rv;  // rv * e_z = v
  rv.col(2) = v;
  rv.col(0) = (Eigen::Vector3d::UnitX() - v.x() * v).normalized();
  rv.col(1) = rv.col(2).cross(rv.col(0));
  const Eigen::Matrix2d b = rv.transpose().topLeftCorner<2, 2>() / ray.norm();
  Eigen::Matrix2d a = b * jacobian;
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(a);
  a /= svd.singularValues()(0);
  const double e = std::sqrt(std::max(0.0, 1 - a(0, 0) * a(0, 0) - a(1, 0) * a(1, 0)));
  double f = std::sqrt(std::max(0.0, 1 - a(0, 1) * a(0, 1) - a(1, 1) * a(1, 1)));
  if (e * f * -(a(0, 0) * a(0, 1) + a(1, 0) * a(1, 1)) < 0) f = -f;  // e f = -(a00 a01 + a10 a11)
  std::array<Eigen::Matrix3d, 2> rotations;
  for (int k = 0; k < 2; ++k) {
    const double sign = k == 0 ? 1 : -1;
    Eigen::Matrix3d local;
    local.col(0) = Eigen::Vector3d(a(0, 0), a(1, 0), sign * e);
    local.col(1) = Eigen::Vector3d(a(0, 1), a(1, 1), sign * f);
    local.col(2) = local.col(0).cross(local.col(1));
    const Eigen::JacobiSVD<Eigen::Matrix3d> nearest(local, Eigen::ComputeFullU | Eigen::ComputeFullV);
    rotations[k] = rv * nearest.matrixU() * nearest.matrixV().transpose();
  }
  return rotations;
}

// The translation that, with rotation fixed, best satisfies the projection equations
// (X - u Z = 0, Y - v Z = 0 for each point: linear in t).
bool translation_for(const Eigen::Matrix3d& rotation, std::span<const Eigen::Vector2d> plane,
                     std::span<const Eigen::Vector2d> image, Eigen::Vector3d& translation) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < plane.size(); ++i) {
    Eigen::Matrix<double, 2, 3> c;
    c << 1, 0, -image[i].x(), 0, 1, -image[i].y();
    const Eigen::Matrix3d ctc = c.transpose() * c;
    normal += ctc;
    rhs -= ctc * (rotation * Eigen::Vector3d(plane[i].x(), plane[i].y(), 0));
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(normal);
  if (!lu.isInvertible()) return false;
  translation = lu.solve(rhs);
  return translation.allFinite();
}

// Sum of squared pixel residuals of a pose, and optionally J^T J and J^T r over (w, dt).
bool reprojection(const RigidTransform& pose, std::span<const Eigen::Vector2d> plane,
                  std::span<const Eigen::Vector2d> pixels, const CameraModel& camera, double& sum_squares,
                  Matrix6d* jtj = nullptr, Vector6d* jtr = nullptr) {
  sum_squares = 0;
  if (jtj) jtj->setZero();
  if (jtr) jtr->setZero();
  for (std::size_t i = 0; i < plane.size(); ++i) {
    const Eigen::Vector3d rotated = pose.rotation * Eigen::Vector3d(plane[i].x(), plane[i].y(), 0);
    const Eigen::Vector3d point_c = rotated + pose.translation;
    if (point_c.z() <= 0) return false;
    Eigen::Vector2d pixel;
    Eigen::Matrix<double, 2, 3> d_pixel;
    if (!camera.project(point_c, pixel, d_pixel)) return false;
    const Eigen::Vector2d residual = pixel - pixels[i];
    sum_squares += residual.squaredNorm();
    if (jtj) {
      Eigen::Matrix<double, 2, 6> j;
      j.leftCols<3>() = -d_pixel * skew(rotated);
      j.rightCols<3>() = d_pixel;
      jtj->noalias() += j.transpose() * j;
      jtr->noalias() += j.transpose() * residual;
    }
  }
  return true;
}

// Levenberg-Marquardt from a start pose; false when the start has a point behind the camera.
bool refine(RigidTransform& pose, std::span<const Eigen::Vector2d> plane, std::span<const Eigen::Vector2d> pixels,
            const CameraModel& camera, double& sum_squares) {
  Matrix6d jtj;
  Vector6d jtr;
  if (!reprojection(pose, plane, pixels, camera, sum_squares, &jtj, &jtr)) return false;
  double lambda = 1e-4;
  for (int iteration = 0; iteration < 100 && lambda < 1e12; ++iteration) {
    Matrix6d damped = jtj;
    damped.diagonal() *= 1 + lambda;
    const Vector6d step = damped.ldlt().solve(-jtr);
    if (!step.allFinite()) return false;
    RigidTransform trial;
    const double angle = step.head<3>().norm();
    trial.rotation = angle > 0 ? Eigen::AngleAxisd(angle, step.head<3>() / angle).toRotationMatrix() * pose.rotation
                               : pose.rotation;
    trial.translation = pose.translation + step.tail<3>();
    double trial_sum = 0;
    if (reprojection(trial, plane, pixels, camera, trial_sum) && trial_sum < sum_squares) {
      const bool converged = sum_squares - trial_sum < 1e-12 * (1 + sum_squares);
      pose = trial;
      reprojection(pose, plane, pixels, camera, sum_squares, &jtj, &jtr);
      lambda = std::max(lambda / 10, 1e-12);
      if (converged) break;
    } else {
      lambda *= 10;
    }
  }
  return true;
}

}  // namespace

PlanarPose solve_planar_pnp(std::span<const Eigen::Vector2d> plane_points, std::span<const Eigen::Vector2d> pixels,
                            const CameraModel& camera) {
  PlanarPose result;
  result.other_sum_squares_px2 = std::numeric_limits<double>::infinity();
  const std::size_t n = plane_points.size();
  if (n < 4 || pixels.size() != n) return result;
  // Normalized image points, at most as many as a floor reference holds: start-up sizes.
  constexpr std::size_t kMaxPoints = 64;
  if (n > kMaxPoints) return result;
  std::array<Eigen::Vector2d, kMaxPoints> image_storage;
  std::array<Eigen::Vector2d, kMaxPoints> centred_storage;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d bearing;
    if (!camera.unproject(pixels[i], bearing) || bearing.z() <= 0) return result;
    image_storage[i] = bearing.head<2>() / bearing.z();
  }
  const std::span<const Eigen::Vector2d> image(image_storage.data(), n);
  Eigen::Vector2d plane_mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& point : plane_points) plane_mean += point;
  plane_mean /= static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) centred_storage[i] = plane_points[i] - plane_mean;
  const std::span<const Eigen::Vector2d> centred(centred_storage.data(), n);

  // From centred plane points to normalized image points, H(2, 2) = 1 (the plane's mean is in view).
  Eigen::Matrix3d homography;
  if (!fit_homography(centred, image, homography)) return result;
  const Eigen::Vector2d origin(homography(0, 2), homography(1, 2));
  Eigen::Matrix2d jacobian;
  jacobian << homography(0, 0) - homography(2, 0) * origin.x(), homography(0, 1) - homography(2, 1) * origin.x(),
              homography(1, 0) - homography(2, 0) * origin.y(), homography(1, 1) - homography(2, 1) * origin.y();
  const Eigen::Vector3d mean(plane_mean.x(), plane_mean.y(), 0);
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Matrix3d& rotation : ippe_rotations(origin, jacobian)) {
    Eigen::Vector3d centred_translation;
    if (!translation_for(rotation, centred, image, centred_translation)) continue;
    RigidTransform pose{rotation, centred_translation - rotation * mean};
    double sum_squares = 0;
    if (!refine(pose, plane_points, pixels, camera, sum_squares)) continue;
    if (sum_squares < best) {
      result.other_sum_squares_px2 = best;
      best = sum_squares;
      result.camera_from_plane = pose;
    } else {
      result.other_sum_squares_px2 = std::min(result.other_sum_squares_px2, sum_squares);
    }
  }
  if (!std::isfinite(best)) return result;
  Vector6d unused;
  reprojection(result.camera_from_plane, plane_points, pixels, camera, result.sum_squares_px2, &result.information, &unused);
  result.ok = true;
  return result;
}

}  // namespace irloc
