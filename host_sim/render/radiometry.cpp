#include "host_sim/render/radiometry.hpp"

#include <algorithm>
#include <cmath>

namespace irloc::sim {

double beam_exponent(double half_angle) { return std::log(0.5) / std::log(std::cos(half_angle)); }

double led_intensity(double on_axis_intensity, double exponent, double cos_off_axis) {
  if (cos_off_axis <= 0) return 0;
  return on_axis_intensity * std::pow(cos_off_axis, exponent);
}

double retro_factor(const RetroReflector& retro, double observation_angle, double entrance_angle) {
  if (entrance_angle >= retro.entrance_limit) return 0;
  const double observation = observation_angle / retro.observation_width;
  const double entrance = entrance_angle / retro.entrance_limit;
  return retro.coefficient * std::exp(-observation * observation) * (1 - entrance * entrance);
}

double landmark_intensity(const LedLandmark& landmark, double on_axis_intensity, const Eigen::Vector3d& viewer) {
  if (!landmark.direction) return on_axis_intensity;
  const double cos_theta = landmark.direction->dot((viewer - landmark.position).normalized());
  if (cos_theta <= 0) return 0;
  if (landmark.half_angle && std::acos(std::min(1.0, cos_theta)) > *landmark.half_angle) return 0;
  return on_axis_intensity * cos_theta;
}

RingIllumination::RingIllumination(const LedRing& ring, const Eigen::Isometry3d& t_w_c)
    : camera_centre_(t_w_c.translation()) {
  for (const LedType& type : ring.types) {
    std::vector<float> table(kTableSize + 2);
    const double exponent = beam_exponent(type.half_angle);
    for (int i = 0; i <= kTableSize + 1; ++i) {
      const double s = std::min(1.0, static_cast<double>(i) / kTableSize);
      table[static_cast<std::size_t>(i)] = static_cast<float>(led_intensity(type.intensity, exponent, 1 - s * s));
    }
    tables_.push_back(std::move(table));
  }
  leds_.reserve(ring.leds.size());
  for (const RingLed& led : ring.leds) {
    leds_.push_back({t_w_c * led.position, t_w_c.linear() * led.axis, led.type});
  }
}

double RingIllumination::intensity(const Led& led, double cos_off_axis) const {
  if (cos_off_axis <= 0) return 0;
  const double position = std::sqrt(std::max(0.0, 1 - cos_off_axis)) * kTableSize;
  const int index = static_cast<int>(position);
  const double fraction = position - index;
  const float* table = tables_[led.type].data();
  return table[index] + fraction * (table[index + 1] - table[index]);
}

double RingIllumination::irradiance(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const {
  double sum = 0;
  for (const Led& led : leds_) {
    const Eigen::Vector3d to_point = point - led.position;
    const double distance2 = to_point.squaredNorm();
    const Eigen::Vector3d direction = to_point / std::sqrt(distance2);
    const double cos_incidence = -direction.dot(normal);
    if (cos_incidence <= 0) continue;
    sum += intensity(led, direction.dot(led.axis)) * cos_incidence / distance2;
  }
  return sum;
}

double RingIllumination::retro_radiance(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                        const RetroReflector& retro) const {
  const Eigen::Vector3d to_camera = (camera_centre_ - point).normalized();
  double sum = 0;
  for (const Led& led : leds_) {
    const Eigen::Vector3d to_led = led.position - point;
    const double distance2 = to_led.squaredNorm();
    const Eigen::Vector3d direction = to_led / std::sqrt(distance2);
    const double cos_entrance = direction.dot(normal);
    if (cos_entrance <= 0) continue;
    const double entrance = std::acos(std::min(1.0, cos_entrance));
    const double observation = std::acos(std::clamp(direction.dot(to_camera), -1.0, 1.0));
    sum += intensity(led, -direction.dot(led.axis)) / distance2 * retro_factor(retro, observation, entrance);
  }
  return sum;
}

}  // namespace irloc::sim
