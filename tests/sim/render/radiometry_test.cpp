// The radiometric model: LED beams, retro-reflection, distance attenuation and emission cones,
// both as functions and as the renderer applies them.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/render/radiometry.hpp"
#include "host_sim/render/renderer.hpp"
#include "tests/support/scenario_text.hpp"

namespace irloc::sim {
namespace {

TEST(Radiometry, LedBeamHalvesAtItsHalfAngle) {
  const double m = beam_exponent(0.4);
  EXPECT_NEAR(led_intensity(2.0, m, 1.0), 2.0, 1e-12);
  EXPECT_NEAR(led_intensity(2.0, m, std::cos(0.4)), 1.0, 1e-12);
  EXPECT_EQ(led_intensity(2.0, m, -0.1), 0.0);
  EXPECT_GT(led_intensity(2.0, m, std::cos(0.3)), led_intensity(2.0, m, std::cos(0.5)));
}

TEST(Radiometry, RetroFactorFallsWithObservationAndEntranceAngle) {
  const RetroReflector retro;
  EXPECT_NEAR(retro_factor(retro, 0, 0), retro.coefficient, 1e-12);
  EXPECT_NEAR(retro_factor(retro, retro.observation_width, 0), retro.coefficient / std::exp(1.0), 1e-9);
  double previous = retro_factor(retro, 0, 0);
  for (double beta = 0.1; beta < retro.entrance_limit; beta += 0.1) {
    const double value = retro_factor(retro, 0, beta);
    EXPECT_LT(value, previous);
    previous = value;
  }
  EXPECT_EQ(retro_factor(retro, 0, retro.entrance_limit + 0.01), 0.0);
}

// One LED on the lens axis, the camera looking straight up at a retro-reflector.
LedRing single_led(double half_angle) {
  LedRing ring;
  ring.types.push_back({"led", 1.0, half_angle});
  ring.leds.push_back({0, Eigen::Vector3d(0.02, 0, 0), Eigen::Vector3d::UnitZ()});
  return ring;
}

TEST(Radiometry, RingIlluminationMatchesTheModelEquation) {
  const LedRing ring = single_led(0.3);
  const RetroReflector retro;
  Eigen::Isometry3d t_w_c = Eigen::Isometry3d::Identity();
  t_w_c.translation() = Eigen::Vector3d(0.1, 0.2, 0.3);
  const RingIllumination illumination(ring, t_w_c);
  const double m = beam_exponent(0.3);
  const Eigen::Vector3d led = t_w_c * ring.leds[0].position;
  const Eigen::Vector3d normal(0, 0, -1);
  for (const Eigen::Vector3d& point : {Eigen::Vector3d(0.1, 0.2, 2.5), Eigen::Vector3d(0.9, -0.4, 2.5),
                                       Eigen::Vector3d(-0.6, 0.3, 3.0)}) {
    const Eigen::Vector3d to_led = led - point;
    const double d = to_led.norm();
    const double cos_off_axis = (point - led).normalized().z();  // the LED's axis is +z
    const double beta = std::acos(to_led.normalized().dot(normal));
    const double alpha = std::acos(to_led.normalized().dot((t_w_c.translation() - point).normalized()));
    const double expected = led_intensity(1.0, m, cos_off_axis) / (d * d) * retro_factor(retro, alpha, beta);
    EXPECT_NEAR(illumination.retro_radiance(point, normal, retro), expected, 1e-3 * expected);
    const double irradiance = led_intensity(1.0, m, cos_off_axis) * std::cos(beta) / (d * d);
    EXPECT_NEAR(illumination.irradiance(point, normal), irradiance, 1e-3 * irradiance);
  }
}

TEST(Radiometry, RetroBrightnessFallsMonotonicallyWithDistance) {
  const LedRing ring = single_led(0.5);
  const RetroReflector retro;
  const RingIllumination illumination(ring, Eigen::Isometry3d::Identity());
  // Along one line of sight, so that only the distance changes. Closer than d = offset /
  // observation_width (0.67 m here) the growing observation angle dims the marker faster than
  // 1/d^2 brightens it: the retro-reflector's cone no longer covers the camera.
  double previous = 1e300;
  for (double height = 0.9; height < 6; height += 0.25) {
    const Eigen::Vector3d point = height * Eigen::Vector3d(0.3, 0.1, 1);
    const double value = illumination.retro_radiance(point, Eigen::Vector3d(0, 0, -1), retro);
    EXPECT_GT(value, 0);
    EXPECT_LT(value, previous) << "at " << height << " m";
    previous = value;
  }
}

TEST(Radiometry, LandmarkEmitsOnlyInsideItsCone) {
  LedLandmark landmark;
  landmark.position = Eigen::Vector3d(0, 0, 2.5);
  landmark.direction = Eigen::Vector3d(0, 0, -1);
  landmark.half_angle = 0.5;
  EXPECT_NEAR(landmark_intensity(landmark, 0.1, Eigen::Vector3d(0, 0, 0)), 0.1, 1e-12);
  const double inside = std::tan(0.49) * 2.5, outside = std::tan(0.51) * 2.5;
  EXPECT_GT(landmark_intensity(landmark, 0.1, Eigen::Vector3d(inside, 0, 0)), 0.08);
  EXPECT_EQ(landmark_intensity(landmark, 0.1, Eigen::Vector3d(outside, 0, 0)), 0.0);
  landmark.direction.reset();
  EXPECT_EQ(landmark_intensity(landmark, 0.1, Eigen::Vector3d(outside, 0, 0)), 0.1);
}

// Total radiance of a rendered frame showing one distant LED landmark and nothing else.
double rendered_landmark_light(double distance, double half_angle, double offset) {
  test::ScenarioText text;
  text.calibration =
      "    image_width: 64\n    image_height: 48\n"
      "    camera_matrix: {rows: 3, cols: 3, data: [50, 0, 31.5, 0, 50, 23.5, 0, 0, 1]}\n"
      "    distortion_model: plumb_bob\n"
      "    distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  text.map = "  led_landmarks:\n    - {name: L, position: [" + std::to_string(offset) + ", 0, " +
             std::to_string(0.3 + distance) + "], direction: [0, 0, -1], half_angle: " + std::to_string(half_angle) + "}\n";
  text.room = "  ceiling_height: " + std::to_string(0.3 + distance + 0.5) + "\n  ambient: 0\n  ceiling_reflectance: 0\n";
  text.extra = "render:\n  supersampling: 4\nlandmark_emitters: {intensity: 0.05, radius: 0.1}\n";
  const Scenario scenario = parse_scenario(text.yaml(), "landmark.yaml");
  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera);
  std::vector<float> radiance(static_cast<std::size_t>(renderer.width() * renderer.height()));
  renderer.render(0, false, radiance);
  return std::accumulate(radiance.begin(), radiance.end(), 0.0);
}

TEST(Radiometry, RenderedLandmarkDimsWithDistanceAndVanishesOutsideItsCone) {
  double previous = 1e300;
  for (const double distance : {1.5, 2.5, 4.0}) {
    const double light = rendered_landmark_light(distance, 1.0, 0);
    EXPECT_GT(light, 0);
    EXPECT_LT(light, previous) << distance;
    previous = light;
  }
  // A sub-pixel emitter: the light collected falls as 1 / d^2 (to the anti-aliasing's accuracy).
  EXPECT_NEAR(rendered_landmark_light(4.0, 1.0, 0) / rendered_landmark_light(2.0, 1.0, 0), 0.25, 0.03);
  // 0.6 m off the axis at 2 m: 0.29 rad from the landmark's direction, in view of the camera.
  EXPECT_GT(rendered_landmark_light(2.0, 0.35, 0.6), 0);
  EXPECT_EQ(rendered_landmark_light(2.0, 0.25, 0.6), 0);
}

}  // namespace
}  // namespace irloc::sim
