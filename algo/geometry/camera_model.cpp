#include "algo/geometry/camera_model.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/LU>

namespace irloc {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The first angle in (0, max_angle] where derivative(angle) <= 0, found by a scan and
// bisection; max_angle (meaning "never") when there is none. Start-up only.
template <typename Derivative>
double first_stationary_angle(Derivative derivative, double max_angle) {
  constexpr int kSamples = 4096;
  double previous = 0;
  for (int i = 1; i <= kSamples; ++i) {
    const double angle = max_angle * i / kSamples;
    if (derivative(angle) <= 0) {
      double low = previous, high = angle;
      for (int k = 0; k < 80; ++k) {
        const double mid = 0.5 * (low + high);
        (derivative(mid) > 0 ? low : high) = mid;
      }
      return low;
    }
    previous = angle;
  }
  return max_angle;
}

}  // namespace

CameraModel::CameraModel(const CameraIntrinsics& intrinsics) : intrinsics_(intrinsics) {
  switch (intrinsics_.model) {
    case LensModel::plumb_bob: {
      // Scan the field angle atan(r) rather than r, which covers r in [0, infinity).
      const double scan_limit = 0.5 * kPi * (1 - 1.0 / 4096);
      const double angle = first_stationary_angle(
          [this](double a) {
            double derivative = 0;
            radial_map(std::tan(a), &derivative);
            return derivative;
          },
          scan_limit);
      if (angle >= scan_limit) {
        max_field_angle_ = 0.5 * kPi;
        max_radius_ = kInfinity;
        max_distorted_radius_ = kInfinity;
      } else {
        max_field_angle_ = angle;
        max_radius_ = std::tan(angle);
        max_distorted_radius_ = radial_map(max_radius_, nullptr);
      }
      break;
    }
    case LensModel::equidistant:
    case LensModel::equisolid:
      max_field_angle_ = first_stationary_angle(
          [this](double theta) {
            double derivative = 0;
            radial_map(theta, &derivative);
            return derivative;
          },
          kPi);
      max_distorted_radius_ = radial_map(max_field_angle_, nullptr);
      break;
  }
}

double CameraModel::radial_map(double x, double* derivative) const {
  const auto& d = intrinsics_.distortion;
  const double x2 = x * x;
  switch (intrinsics_.model) {
    case LensModel::plumb_bob: {  // r (1 + k1 r^2 + k2 r^4 + k3 r^6)
      const double k1 = d[0], k2 = d[1], k3 = d[4];
      if (derivative) *derivative = 1 + x2 * (3 * k1 + x2 * (5 * k2 + x2 * 7 * k3));
      return x * (1 + x2 * (k1 + x2 * (k2 + x2 * k3)));
    }
    case LensModel::equidistant: {  // theta (1 + k1 theta^2 + ... + k4 theta^8)
      const double k1 = d[0], k2 = d[1], k3 = d[2], k4 = d[3];
      if (derivative) *derivative = 1 + x2 * (3 * k1 + x2 * (5 * k2 + x2 * (7 * k3 + x2 * 9 * k4)));
      return x * (1 + x2 * (k1 + x2 * (k2 + x2 * (k3 + x2 * k4))));
    }
    case LensModel::equisolid:  // 2 sin(theta / 2)
      if (derivative) *derivative = std::cos(0.5 * x);
      return 2 * std::sin(0.5 * x);
  }
  return 0;
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& xy, Eigen::Matrix2d* jacobian) const {
  const auto& d = intrinsics_.distortion;
  const double k1 = d[0], k2 = d[1], p1 = d[2], p2 = d[3], k3 = d[4];
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const Eigen::Vector2d distorted(x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x),
                                  y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y);
  if (jacobian) {
    const double d_radial_d_r2 = k1 + r2 * (2 * k2 + r2 * 3 * k3);
    // d radial / dx = 2 x d_radial_d_r2, likewise for y.
    (*jacobian)(0, 0) = radial + 2 * x * x * d_radial_d_r2 + 2 * p1 * y + 6 * p2 * x;
    (*jacobian)(0, 1) = 2 * x * y * d_radial_d_r2 + 2 * p1 * x + 2 * p2 * y;
    (*jacobian)(1, 0) = 2 * x * y * d_radial_d_r2 + 2 * p1 * x + 2 * p2 * y;
    (*jacobian)(1, 1) = radial + 2 * y * y * d_radial_d_r2 + 6 * p1 * y + 2 * p2 * x;
  }
  return distorted;
}

bool CameraModel::project_pinhole(const Eigen::Vector3d& p, Eigen::Vector2d& m,
                                  Eigen::Matrix<double, 2, 3>* d_m_d_point) const {
  if (!(p.z() > 0)) return false;
  const double inv_z = 1 / p.z();
  const Eigen::Vector2d xy(p.x() * inv_z, p.y() * inv_z);
  if (!(xy.squaredNorm() < max_radius_ * max_radius_)) return false;
  Eigen::Matrix2d d_m_d_xy;
  m = distort(xy, d_m_d_point ? &d_m_d_xy : nullptr);
  if (d_m_d_point) {
    Eigen::Matrix<double, 2, 3> d_xy_d_point;
    d_xy_d_point << inv_z, 0, -xy.x() * inv_z, 0, inv_z, -xy.y() * inv_z;
    *d_m_d_point = d_m_d_xy * d_xy_d_point;
  }
  return true;
}

bool CameraModel::project_radial(const Eigen::Vector3d& p, Eigen::Vector2d& m,
                                 Eigen::Matrix<double, 2, 3>* d_m_d_point) const {
  const double rho2 = p.x() * p.x() + p.y() * p.y();
  const double rho = std::sqrt(rho2);
  const double norm2 = rho2 + p.z() * p.z();
  if (!(norm2 > 0)) return false;
  const double theta = std::atan2(rho, p.z());
  if (!(theta < max_field_angle_)) return false;
  double g_prime = 0;
  const double g = radial_map(theta, &g_prime);
  // m = (g(theta) / rho) (x, y); near the axis g(theta) / rho -> 1 / z since g'(0) = 1. Next to
  // the backward axis the azimuth is lost in rounding: outside the valid region.
  if (rho <= 1e-12 * std::sqrt(norm2)) {
    if (p.z() < 0) return false;
    const double inv_z = 1 / p.z();
    m = Eigen::Vector2d(p.x() * inv_z, p.y() * inv_z);
    if (d_m_d_point) {
      *d_m_d_point << inv_z, 0, -p.x() * inv_z * inv_z, 0, inv_z, -p.y() * inv_z * inv_z;
    }
    return true;
  }
  const double scale = g / rho;
  m = Eigen::Vector2d(scale * p.x(), scale * p.y());
  if (d_m_d_point) {
    // d scale / d point = (g' / rho) d theta / d point - (g / rho^2) d rho / d point.
    const double a = g_prime * p.z() / (rho2 * norm2) - g / (rho2 * rho);
    const Eigen::RowVector3d d_scale(a * p.x(), a * p.y(), -g_prime / norm2);
    *d_m_d_point = Eigen::Vector2d(p.x(), p.y()) * d_scale;
    (*d_m_d_point)(0, 0) += scale;
    (*d_m_d_point)(1, 1) += scale;
  }
  return true;
}

bool CameraModel::project_normalized(const Eigen::Vector3d& point_c, Eigen::Vector2d& m,
                                     Eigen::Matrix<double, 2, 3>* d_m_d_point) const {
  return intrinsics_.model == LensModel::plumb_bob ? project_pinhole(point_c, m, d_m_d_point)
                                                   : project_radial(point_c, m, d_m_d_point);
}

bool CameraModel::project(const Eigen::Vector3d& point_c, Eigen::Vector2d& pixel) const {
  Eigen::Vector2d m;
  if (!project_normalized(point_c, m, nullptr)) return false;
  pixel = Eigen::Vector2d(intrinsics_.fx * m.x() + intrinsics_.cx,
                          intrinsics_.fy * m.y() + intrinsics_.cy);
  return true;
}

bool CameraModel::project(const Eigen::Vector3d& point_c, Eigen::Vector2d& pixel,
                          Eigen::Matrix<double, 2, 3>& d_pixel_d_point) const {
  Eigen::Vector2d m;
  if (!project_normalized(point_c, m, &d_pixel_d_point)) return false;
  pixel = Eigen::Vector2d(intrinsics_.fx * m.x() + intrinsics_.cx,
                          intrinsics_.fy * m.y() + intrinsics_.cy);
  d_pixel_d_point.row(0) *= intrinsics_.fx;
  d_pixel_d_point.row(1) *= intrinsics_.fy;
  return true;
}

bool CameraModel::unproject(const Eigen::Vector2d& pixel, Eigen::Vector3d& bearing) const {
  const Eigen::Vector2d m((pixel.x() - intrinsics_.cx) / intrinsics_.fx,
                          (pixel.y() - intrinsics_.cy) / intrinsics_.fy);
  if (!m.allFinite()) return false;
  return intrinsics_.model == LensModel::plumb_bob ? unproject_pinhole(m, bearing)
                                                   : unproject_radial(m, bearing);
}

namespace {

// Solves map(x) = target for x in [0, upper) where map is increasing from map(0) = 0 with
// map(upper) >= target: Newton steps, falling back to bisection when a step leaves the bracket.
template <typename Map>
double invert_increasing(Map map, double target, double upper) {
  double low = 0, high = upper;
  double x = target < upper ? target : 0.5 * upper;
  for (int i = 0; i < 100; ++i) {
    double derivative = 0;
    const double error = map(x, &derivative) - target;
    if (error == 0) return x;
    (error < 0 ? low : high) = x;
    double next = x - error / derivative;
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - x) <= 1e-16 * (1 + x)) return next;
    x = next;
  }
  return x;
}

}  // namespace

bool CameraModel::unproject_radial(const Eigen::Vector2d& m, Eigen::Vector3d& bearing) const {
  const double distorted_radius = m.norm();
  if (!(distorted_radius < max_distorted_radius_)) return false;
  if (distorted_radius == 0) {
    bearing = Eigen::Vector3d::UnitZ();
    return true;
  }
  double theta = 0;
  if (intrinsics_.model == LensModel::equisolid) {
    theta = 2 * std::asin(0.5 * distorted_radius);
  } else {
    theta = invert_increasing([this](double t, double* d) { return radial_map(t, d); },
                              distorted_radius, max_field_angle_);
  }
  const double scale = std::sin(theta) / distorted_radius;
  bearing = Eigen::Vector3d(scale * m.x(), scale * m.y(), std::cos(theta));
  return true;
}

bool CameraModel::unproject_pinhole(const Eigen::Vector2d& m, Eigen::Vector3d& bearing) const {
  // Start from the radial-only inverse (exact without tangential terms), then Newton on the full
  // 2-D map.
  const double distorted_radius = m.norm();
  Eigen::Vector2d xy = m;
  if (distorted_radius > 0) {
    double upper = max_radius_;
    // Beyond max_distorted_radius_ this start ends near r_max; tangential terms may still bring
    // the point inside, and the checks below decide.
    if (std::isinf(upper)) {
      upper = 2 * distorted_radius;
      while (radial_map(upper, nullptr) < distorted_radius && upper < 1e12) upper *= 2;
    }
    const double radius = invert_increasing(
        [this](double r, double* d) { return radial_map(r, d); }, distorted_radius, upper);
    xy = m * (radius / distorted_radius);
  }
  Eigen::Vector2d residual = Eigen::Vector2d::Zero();
  for (int i = 0; i < 20; ++i) {
    Eigen::Matrix2d jacobian;
    residual = distort(xy, &jacobian) - m;
    if (residual.norm() <= 1e-15 * (1 + distorted_radius)) break;
    xy -= jacobian.inverse() * residual;
  }
  residual = distort(xy, nullptr) - m;
  if (!(residual.norm() <= 1e-11 * (1 + distorted_radius))) return false;
  if (!(xy.squaredNorm() < max_radius_ * max_radius_)) return false;
  bearing = Eigen::Vector3d(xy.x(), xy.y(), 1).normalized();
  return true;
}

bool CameraModel::in_image(const Eigen::Vector2d& pixel) const {
  return pixel.x() >= -0.5 && pixel.x() <= intrinsics_.width - 0.5 && pixel.y() >= -0.5 &&
         pixel.y() <= intrinsics_.height - 0.5;
}

}  // namespace irloc
