#include "algo/markers/outside_in/floor_geometry.hpp"

#include <cmath>
#include <cstdio>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/planar_pnp.hpp"

namespace irloc::outside_in {
namespace {

FloorGeometry fail(std::string error) {
  FloorGeometry geometry;
  geometry.error = std::move(error);
  return geometry;
}

std::string fixed(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

// The x beyond which chi-square with k (even) degrees of freedom has probability p:
// P(X > x) = exp(-x/2) sum_{i < k/2} (x/2)^i / i!, solved by bisection.
double chi_square_quantile_even(int k, double p) {
  const auto survival = [k](double x) {
    double term = 1, sum = 1;
    for (int i = 1; i < k / 2; ++i) sum += term *= (x / 2) / i;
    return std::exp(-x / 2) * sum;
  };
  double low = 0, high = 10.0 * k + 100;
  for (int i = 0; i < 100; ++i) {
    const double middle = 0.5 * (low + high);
    (survival(middle) > 1 - p ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace

FloorGeometry solve_floor_geometry(const CameraIntrinsics& camera, const FloorReference& reference) {
  const auto& w = reference.world;
  const std::size_t n = w.size();
  if (n < 4 || n > FloorReference::kMaxPoints)
    return fail("floor_reference.world: expected 4 to " + std::to_string(FloorReference::kMaxPoints) + " points, got " +
                std::to_string(n));
  if (reference.pixels.size() != n)
    return fail("floor_reference.pixels: expected one pixel per world point (" + std::to_string(n) + "), got " +
                std::to_string(reference.pixels.size()));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if ((w[i] - w[j]).norm() < 0.05)
        return fail("floor_reference.world: points " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                    " are closer than 5 cm");
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : w) mean += p;
  mean /= static_cast<double>(n);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : w) scatter += (p - mean) * (p - mean).transpose();
  if (std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter / static_cast<double>(n)).eigenvalues()(0)) < 0.02)
    return fail("floor_reference.world: the points lie (nearly) on one line");
  const CameraModel model(camera);
  for (std::size_t i = 0; i < n; ++i) {
    if (!model.in_image(reference.pixels[i]))
      return fail("floor_reference.pixels: point " + std::to_string(i + 1) + " lies outside the image");
    Eigen::Vector3d bearing;
    if (!model.unproject(reference.pixels[i], bearing) || bearing.z() <= 0)
      return fail("floor_reference.pixels: point " + std::to_string(i + 1) + " is outside the lens model's field of view");
  }

  const PlanarPose pose = solve_planar_pnp(w, reference.pixels, model);
  if (!pose.ok) return fail("floor_reference: no camera pose fits the points (pixels and world points in different order?)");
  FloorGeometry geometry;
  geometry.camera_from_world = pose.camera_from_plane;
  if (geometry.camera_from_world.inverse().translation.z() <= 0.05)
    return fail("floor_reference: the camera comes out below the floor (pixels and world points in different order?)");
  geometry.reprojection_rms_px = std::sqrt(pose.sum_squares_px2 / static_cast<double>(n));
  const int freedom = 2 * static_cast<int>(n) - 6;
  const double sigma = reference.pixel_sigma;
  const double limit_rms = sigma * std::sqrt(chi_square_quantile_even(freedom, 0.999) / static_cast<double>(n));
  if (geometry.reprojection_rms_px > limit_rms)
    return fail("floor_reference: the points do not fit one floor seen by this camera (reprojection RMS " +
                fixed(geometry.reprojection_rms_px) + " px > " + fixed(limit_rms) + " px, the most that pixel_sigma " +
                fixed(sigma) + " px allows for " + std::to_string(n) + " points)");
  const double variance = std::max(sigma * sigma, pose.sum_squares_px2 / freedom);
  const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> information(pose.information);
  if (!information.isInvertible()) return fail("floor_reference: the points do not determine the camera pose");
  geometry.covariance = variance * information.inverse();
  geometry.ok = true;
  return geometry;
}

}  // namespace irloc::outside_in
