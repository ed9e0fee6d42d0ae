#pragma once
// The radiometric model of the rendered scenes (docs/simulator.md, "Radiometry"), after the
// square-marker paper: the brightness of a retro-reflector is the sum over the ring's LEDs of
// distance attenuation x LED directivity x retro-reflection factor(observation, entrance angle).
// Radiance in W sr^-1 m^-2, intensity in W/sr, irradiance in W/m^2, angles in radians.

#include <vector>

#include <Eigen/Geometry>

#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// Exponent m of the I0 cos^m(theta) beam whose intensity halves at `half_angle`.
double beam_exponent(double half_angle);

// I0 cos^m(theta) for cos(theta) = cos_off_axis; 0 behind the LED.
double led_intensity(double on_axis_intensity, double exponent, double cos_off_axis);

// Coefficient of retro-reflection (sr^-1): R0 exp(-(alpha / alpha_w)^2) (1 - (beta / beta_max)^2)
// for beta < beta_max, else 0.
double retro_factor(const RetroReflector& retro, double observation_angle, double entrance_angle);

// Intensity (W/sr) an active LED landmark sends toward `viewer`: I0 cos(theta) inside its
// emission cone (theta from its direction), 0 outside; I0 everywhere when it has no direction.
double landmark_intensity(const LedLandmark& landmark, double on_axis_intensity, const Eigen::Vector3d& viewer);

// The robot's LED ring placed in the world for one instant.
class RingIllumination {
 public:
  RingIllumination(const LedRing& ring, const Eigen::Isometry3d& t_w_c);

  // Irradiance (W/m^2) on a surface at `point` with unit `normal` (pointing toward the room).
  double irradiance(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) const;

  // Radiance toward the camera of retro-reflective material at `point` with unit `normal`:
  // sum over LEDs of I_i(theta_i) / d_i^2 x R(alpha_i, beta_i).
  double retro_radiance(const Eigen::Vector3d& point, const Eigen::Vector3d& normal, const RetroReflector& retro) const;

  const Eigen::Vector3d& camera_centre() const { return camera_centre_; }

 private:
  struct Led {
    Eigen::Vector3d position, axis;  // world frame
    std::size_t type;
  };
  // I(theta) of each LED type tabulated over s = sqrt(1 - cos theta), which is close to linear
  // in theta near the axis where narrow beams change fastest; linear interpolation keeps the
  // relative error below 1e-3 (tests/sim checks it) at a fraction of the cost of pow().
  static constexpr int kTableSize = 2048;
  double intensity(const Led& led, double cos_off_axis) const;
  std::vector<std::vector<float>> tables_;
  std::vector<Led> leds_;
  Eigen::Vector3d camera_centre_;
};

}  // namespace irloc::sim
