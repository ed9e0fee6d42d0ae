#include "algo/outside_in/floor_geometry.hpp"

#include <cmath>
#include <Eigen/SVD>

#include "algo/geometry/camera_model.hpp"

namespace irloc {
namespace {

double cross_z(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The signed turn of every corner of a quadrilateral has one sign: it is convex and not crossed.
bool convex(const std::array<Eigen::Vector2d, 4>& p) {
  int positive = 0, negative = 0;
  for (int i = 0; i < 4; ++i) {
    const double turn = cross_z(p[(i + 1) % 4] - p[i], p[(i + 2) % 4] - p[(i + 1) % 4]);
    if (turn > 0) ++positive;
    if (turn < 0) ++negative;
  }
  return positive == 4 || negative == 4;
}

bool close(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance * std::max(a, b); }

FloorGeometry fail(std::string error) {
  FloorGeometry geometry;
  geometry.error = std::move(error);
  return geometry;
}

}  // namespace

FloorGeometry solve_floor_geometry(const CameraIntrinsics& camera, const FloorReference& reference) {
  const auto& w = reference.world;
  const double side[4] = {(w[1] - w[0]).norm(), (w[2] - w[1]).norm(), (w[3] - w[2]).norm(), (w[0] - w[3]).norm()};
  for (double length : side)
    if (length < 0.05) return fail("floor_reference.world: a side is shorter than 5 cm");
  if (!convex(w) || !close(side[0], side[2], 0.02) || !close(side[1], side[3], 0.02) ||
      !close((w[2] - w[0]).norm(), (w[3] - w[1]).norm(), 0.02))
    return fail("floor_reference.world: the four corners are not a rectangle in order around it");
  for (const Eigen::Vector2d& pixel : reference.pixels)
    if (pixel.x() < -0.5 || pixel.y() < -0.5 || pixel.x() > camera.width - 0.5 || pixel.y() > camera.height - 0.5)
      return fail("floor_reference.pixels: a corner lies outside the image");
  if (!convex(reference.pixels))
    return fail("floor_reference.pixels: the four corners are not a convex quadrilateral in order around it");

  const CameraModel model(camera);
  std::array<Eigen::Vector2d, 4> normalized;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector3d bearing;
    if (!model.unproject(reference.pixels[i], bearing) || bearing.z() <= 0)
      return fail("floor_reference.pixels: a corner is outside the lens model's field of view");
    normalized[i] = bearing.head<2>() / bearing.z();
  }
  // DLT: each correspondence gives two rows of A h = 0 for the 3x3 homography H (row-major h).
  Eigen::Matrix<double, 9, 9> a = Eigen::Matrix<double, 9, 9>::Zero();
  for (int i = 0; i < 4; ++i) {
    const double x = w[i].x(), y = w[i].y(), u = normalized[i].x(), v = normalized[i].y();
    a.row(2 * i) << x, y, 1, 0, 0, 0, -u * x, -u * y, -u;
    a.row(2 * i + 1) << 0, 0, 0, x, y, 1, -v * x, -v * y, -v;
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, 9, 9>> svd(a, Eigen::ComputeFullV);
  const Eigen::Matrix<double, 9, 1> h = svd.matrixV().col(8);
  Eigen::Matrix3d homography;
  homography << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  // H ~ [r1 r2 t]; the reference rectangle is seen, so its centre is in front of the camera (the
  // world origin need not be: a camera may look away from it).
  double scale = 2.0 / (homography.col(0).norm() + homography.col(1).norm());
  const Eigen::Vector2d centre = 0.25 * (w[0] + w[1] + w[2] + w[3]);
  if ((homography * Eigen::Vector3d(centre.x(), centre.y(), 1)).z() < 0) scale = -scale;
  Eigen::Matrix3d rotation;
  rotation.col(0) = scale * homography.col(0);
  rotation.col(1) = scale * homography.col(1);
  rotation.col(2) = rotation.col(0).cross(rotation.col(1));
  const Eigen::JacobiSVD<Eigen::Matrix3d> nearest(rotation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  rotation = nearest.matrixU() * nearest.matrixV().transpose();
  if (rotation.determinant() < 0) return fail("floor_reference: the corners give a mirrored camera (wrong order?)");

  FloorGeometry geometry;
  geometry.camera_from_world = {rotation, scale * homography.col(2)};
  const Eigen::Vector3d camera_in_world = geometry.camera_from_world.inverse().translation;
  if (camera_in_world.z() <= 0.05)
    return fail("floor_reference: the camera comes out below the floor (pixels and world corners in different order?)");
  double sum_squares = 0;
  for (int i = 0; i < 4; ++i) {
    Eigen::Vector2d pixel;
    if (!model.project(geometry.camera_from_world * Eigen::Vector3d(w[i].x(), w[i].y(), 0), pixel))
      return fail("floor_reference: a corner does not project back into the image");
    sum_squares += (pixel - reference.pixels[i]).squaredNorm();
  }
  geometry.reprojection_rms_px = std::sqrt(sum_squares / 4);
  if (geometry.reprojection_rms_px > 3)
    return fail("floor_reference: the corners do not fit one rectangle seen by this camera (reprojection " +
                std::to_string(geometry.reprojection_rms_px) + " px > 3 px)");
  geometry.ok = true;
  return geometry;
}

}  // namespace irloc
