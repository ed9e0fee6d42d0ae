#include "algo/calibration/lens_parameters.hpp"

#include <cmath>

namespace irloc::calibration {

int lens_parameter_count(LensModel model) {
  switch (model) {
    case LensModel::plumb_bob: return 9;
    case LensModel::equidistant: return 8;
    case LensModel::equisolid: return 4;
  }
  return 4;
}

const char* lens_parameter_name(LensModel model, int index) {
  static constexpr const char* kCommon[] = {"fx", "fy", "cx", "cy"};
  static constexpr const char* kPlumbBob[] = {"k1", "k2", "p1", "p2", "k3"};
  static constexpr const char* kEquidistant[] = {"k1", "k2", "k3", "k4"};
  if (index < 4) return kCommon[index];
  return model == LensModel::plumb_bob ? kPlumbBob[index - 4] : kEquidistant[index - 4];
}

double lens_parameter(const CameraIntrinsics& k, int index) {
  switch (index) {
    case 0: return k.fx;
    case 1: return k.fy;
    case 2: return k.cx;
    case 3: return k.cy;
    default: return k.distortion[static_cast<std::size_t>(index - 4)];
  }
}

void set_lens_parameter(CameraIntrinsics& k, int index, double value) {
  switch (index) {
    case 0: k.fx = value; break;
    case 1: k.fy = value; break;
    case 2: k.cx = value; break;
    case 3: k.cy = value; break;
    default: k.distortion[static_cast<std::size_t>(index - 4)] = value; break;
  }
}

LensJacobian lens_jacobian(const CameraIntrinsics& k, const Eigen::Vector3d& point_c, const Eigen::Vector2d& pixel) {
  LensJacobian jacobian = LensJacobian::Zero();
  // The distorted normalized coordinates, recovered from the pixel: u = cx + fx m_x.
  const double mx = (pixel.x() - k.cx) / k.fx;
  const double my = (pixel.y() - k.cy) / k.fy;
  jacobian(0, 0) = mx;
  jacobian(1, 1) = my;
  jacobian(0, 2) = 1;
  jacobian(1, 3) = 1;
  switch (k.model) {
    case LensModel::plumb_bob: {
      // m = xy (1 + k1 r^2 + k2 r^4 + k3 r^6) + (2 p1 x y + p2 (r^2 + 2 x^2), p1 (r^2 + 2 y^2) + 2 p2 x y)
      const double x = point_c.x() / point_c.z(), y = point_c.y() / point_c.z();
      const double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
      const double d[5][2] = {{x * r2, y * r2}, {x * r4, y * r4}, {2 * x * y, r2 + 2 * y * y}, {r2 + 2 * x * x, 2 * x * y},
                              {x * r6, y * r6}};
      for (int i = 0; i < 5; ++i) {
        jacobian(0, 4 + i) = k.fx * d[i][0];
        jacobian(1, 4 + i) = k.fy * d[i][1];
      }
      break;
    }
    case LensModel::equidistant: {
      // m = theta (1 + k1 theta^2 + ... + k4 theta^8) (x, y) / |(x, y)|, theta from the optical axis.
      const double planar = std::hypot(point_c.x(), point_c.y());
      if (planar == 0) break;
      const double theta = std::atan2(planar, point_c.z());
      const double cos_phi = point_c.x() / planar, sin_phi = point_c.y() / planar;
      double power = theta * theta * theta;
      for (int i = 0; i < 4; ++i) {
        jacobian(0, 4 + i) = k.fx * power * cos_phi;
        jacobian(1, 4 + i) = k.fy * power * sin_phi;
        power *= theta * theta;
      }
      break;
    }
    case LensModel::equisolid: break;
  }
  return jacobian;
}

}  // namespace irloc::calibration
