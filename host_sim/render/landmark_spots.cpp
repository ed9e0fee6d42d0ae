#include "host_sim/render/landmark_spots.hpp"

#include <algorithm>
#include <cmath>

#include "host_sim/render/radiometry.hpp"

namespace irloc::sim {
namespace {

// Share of a unit Gaussian centred at `centre` (sigma in pixels) falling on pixel index i, which
// spans [i - 0.5, i + 0.5].
double pixel_share(int i, double centre, double sigma) {
  const double scale = 1.0 / (std::sqrt(2.0) * sigma);
  return 0.5 * (std::erf((i + 0.5 - centre) * scale) - std::erf((i - 0.5 - centre) * scale));
}

// One landmark's spot as seen from camera pose t_w_c.
void add_spot(const Scenario& scenario, const CameraModel& camera, const LedLandmark& landmark,
              const Eigen::Isometry3d& t_w_c, double weight, std::span<float> radiance) {
  const double sigma = scenario.landmark_emitters.psf_sigma;
  const int width = camera.intrinsics().width, height = camera.intrinsics().height;
  const int reach = static_cast<int>(std::ceil(5 * sigma));
  const double intensity = landmark_intensity(landmark, scenario.landmark_emitters.intensity, t_w_c.translation());
  if (intensity <= 0) return;
  const Eigen::Vector3d point = t_w_c.inverse() * landmark.position;
  Eigen::Vector2d centre;
  Eigen::Matrix<double, 2, 3> d_pixel_d_point;
  if (!camera.project(point, centre, d_pixel_d_point)) return;
  // Pixels per steradian around the LED's direction: the Jacobian of the projection over the
  // plane perpendicular to the ray, at unit distance.
  const double distance = point.norm();
  const Eigen::Vector3d ray = point / distance;
  const Eigen::Vector3d e1 = ray.unitOrthogonal(), e2 = ray.cross(e1);
  Eigen::Matrix2d on_tangent;
  on_tangent << d_pixel_d_point * e1 * distance, d_pixel_d_point * e2 * distance;
  // Mean radiance summed over the spot's pixels: irradiance at the lens times pixels per sr.
  const double total = weight * intensity / (distance * distance) * std::abs(on_tangent.determinant());
  const int cx = static_cast<int>(std::lround(centre.x())), cy = static_cast<int>(std::lround(centre.y()));
  for (int y = std::max(0, cy - reach); y <= std::min(height - 1, cy + reach); ++y) {
    const double share_y = pixel_share(y, centre.y(), sigma);
    for (int x = std::max(0, cx - reach); x <= std::min(width - 1, cx + reach); ++x) {
      radiance[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] +=
          static_cast<float>(total * share_y * pixel_share(x, centre.x(), sigma));
    }
  }
}

}  // namespace

void add_landmark_spots(const Scenario& scenario, const CameraModel& camera, const Eigen::Isometry3d& t_w_c,
                        double weight, std::span<float> radiance) {
  for (const LedLandmark& landmark : scenario.map.led_landmarks) add_spot(scenario, camera, landmark, t_w_c, weight, radiance);
}

void add_landmark_spots(const Scenario& scenario, const CameraModel& camera, const CameraPoseAtRow& t_w_c_at_row,
                        double weight, std::span<float> radiance) {
  // The row moves by (line time x image motion) per row of error: a few passes settle it far
  // below a pixel at robot speeds.
  constexpr int kRowPasses = 4;
  const double last_row = camera.intrinsics().height - 1;
  for (const LedLandmark& landmark : scenario.map.led_landmarks) {
    Eigen::Isometry3d pose = t_w_c_at_row(0);
    for (int pass = 0; pass < kRowPasses; ++pass) {
      Eigen::Vector2d centre;
      if (!camera.project(pose.inverse() * landmark.position, centre)) break;
      pose = t_w_c_at_row(std::clamp(centre.y(), 0.0, last_row));
    }
    add_spot(scenario, camera, landmark, pose, weight, radiance);
  }
}

}  // namespace irloc::sim
