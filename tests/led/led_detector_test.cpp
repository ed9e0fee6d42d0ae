// LED detection on simulator-rendered strobe pairs: sub-pixel centres against the renderer's true
// projections (spots of 1 to 3 px, 8- and 12-bit frames, sensor noise), and what is not an LED.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "algo/markers/led/led_detector.hpp"
#include "tests/led/led_scene.hpp"

namespace irloc::led {
namespace {

using test::LedScene;
using test::led_at;
using test::render_pair;
using test::RenderedPair;

// Worst distance from each scene LED's true projection to the nearest detection.
double worst_centre_error(const LedScene& scene, const test::SceneRadiance& radiance, const LedSourceConfig& config,
                          int* measured) {
  RenderedPair pair;
  test::expose_pair(scene, radiance, pair);
  LedDetector detector(scene.camera.width, scene.camera.height, scene.bit_depth, config);
  LedDetectionList detections;
  LedGlareList glare;
  LedDetectionCounters counters;
  detector.detect(pair.on.image, &pair.off.image, detections, glare, counters);
  double worst = 0;
  *measured = 0;
  for (const LedLandmark& led : scene.scene_leds) {
    const auto truth = scene.project(led.position);
    if (!truth) continue;
    double nearest = 1e9;
    for (const LedDetection& d : detections) nearest = std::min(nearest, (d.pixel - *truth).norm());
    EXPECT_LT(nearest, 1.0) << "LED at " << led.position.transpose() << " not detected";
    worst = std::max(worst, nearest);
    ++*measured;
  }
  return worst;
}

// LEDs 3 to 5 m ahead at sub-pixel offsets all over the image, spot sizes from about 1 px
// (sigma 0.5) to 3 px (sigma 1.1).
LedScene accuracy_scene(double psf_sigma, int bit_depth) {
  LedScene scene;
  scene.psf_sigma = psf_sigma;
  scene.bit_depth = bit_depth;
  for (int i = 0; i < 12; ++i) {
    const double distance = 3.0 + (i % 5) * 0.5;
    scene.scene_leds.push_back(led_at(distance, -1.4 + 0.2637 * i, 0.2 + 0.0871 * i));
  }
  // Brightness in range at every distance: peaks between about 30 and 90 % of full scale.
  scene.intensity = 0.012 * psf_sigma * psf_sigma / 0.49;
  return scene;
}

TEST(LedDetector, SubPixelCentresMatchTheRenderedProjections) {
  LedSourceConfig config;
  config.threshold = 0.12;
  config.off_threshold = 0.08;
  for (const double sigma : {0.5, 0.7, 1.1}) {
    const test::SceneRadiance radiance = test::render_radiance(accuracy_scene(sigma, 8));
    for (const int bits : {8, 12}) {
      int measured = 0;
      const double worst = worst_centre_error(accuracy_scene(sigma, bits), radiance, config, &measured);
      std::printf("psf sigma %.1f px, %d bits: worst centre error %.4f px over %d LEDs\n", sigma, bits, worst,
                  measured);
      EXPECT_EQ(measured, 12);
      EXPECT_LE(worst, 0.05) << "sigma " << sigma << " bits " << bits;
    }
  }
}

TEST(LedDetector, RejectsLampsSunPatchesAndRetroReflectors) {
  LedScene scene;
  scene.scene_leds = {led_at(4, 0.5, 0.8), led_at(4, -0.5, 0.3)};
  scene.lamps = {{100, 50, 180, 58, 40.0f},     // an elongated lamp
                 {400, 300, 480, 380, 40.0f}};  // a large sunlit patch
  scene.on_only = {{200, 400, 202, 402, 60.0f}};  // a retro-reflector: bright only with the LEDs on
  RenderedPair pair;
  render_pair(scene, pair);
  LedSourceConfig config;
  LedDetector detector(640, 480, 8, config);
  LedDetectionList detections;
  LedGlareList glare;
  LedDetectionCounters counters;
  detector.detect(pair.on.image, &pair.off.image, detections, glare, counters);
  ASSERT_EQ(detections.size(), 2u);
  for (const LedDetection& d : detections) {
    const bool near_an_led = (d.pixel - *scene.project(scene.scene_leds[0].position)).norm() < 0.2 ||
                             (d.pixel - *scene.project(scene.scene_leds[1].position)).norm() < 0.2;
    EXPECT_TRUE(near_an_led) << d.pixel.transpose();
  }
  EXPECT_EQ(counters.too_large, 2u);  // the lamp (81 x 9) and the patch are both larger than max_area
  EXPECT_EQ(counters.dark_when_off, 1u);
  // Both are glare, where an LED may hide: their boxes.
  ASSERT_EQ(glare.size(), 2u);
  const bool lamp_first = glare[0].min().y() < glare[1].min().y();
  const Eigen::AlignedBox2d& lamp = glare[lamp_first ? 0 : 1];
  const Eigen::AlignedBox2d& patch = glare[lamp_first ? 1 : 0];
  EXPECT_TRUE(lamp.contains(Eigen::Vector2d(140, 54)) && !lamp.contains(Eigen::Vector2d(140, 62)));
  EXPECT_TRUE(patch.contains(Eigen::Vector2d(401, 301)) && patch.contains(Eigen::Vector2d(479, 379)));
  EXPECT_FALSE(patch.contains(Eigen::Vector2d(390, 340)));
}

TEST(LedDetector, ElongatedSmallSpotsAndCrowdedSpotsAreNotLeds) {
  LedScene scene;
  scene.scene_leds = {led_at(4, 0.0, 0.5)};
  const Eigen::Vector2d led = *scene.project(scene.scene_leds[0].position);
  const int x = static_cast<int>(std::lround(led.x())), y = static_cast<int>(std::lround(led.y()));
  scene.lamps = {{50, 50, 62, 51, 40.0f},            // a thin streak: small but elongated
                 {x + 3, y - 1, x + 9, y + 1, 40.0f}};  // a short lamp right beside the LED
  RenderedPair pair;
  render_pair(scene, pair);
  LedSourceConfig config;
  LedDetector detector(640, 480, 8, config);
  LedDetectionList detections;
  LedGlareList glare;
  LedDetectionCounters counters;
  detector.detect(pair.on.image, &pair.off.image, detections, glare, counters);
  EXPECT_EQ(counters.elongated, 2u);
  // The LED beside the lamp is measured without bias or not at all; the lamp is no LED.
  for (const LedDetection& d : detections) {
    const double distance = (d.pixel - led).norm();
    EXPECT_TRUE(distance < 0.1 || distance > 12.0) << d.pixel.transpose();
  }
}

}  // namespace
}  // namespace irloc::led
