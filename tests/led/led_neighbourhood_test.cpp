// The LEDs near the camera (led_neighbourhood.hpp) against a brute-force scan of the map: every
// LED within range is listed, in the map's order, for maps far larger than one view; a map denser
// than led.max_leds_in_range is refused at start-up.

#include <algorithm>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "algo/markers/led/led_neighbourhood.hpp"
#include "tests/led/led_scene.hpp"

namespace irloc::led {
namespace {

std::vector<LedLandmark> scattered_leds(std::size_t count, double side, std::mt19937& random) {
  std::uniform_real_distribution<double> along(-side / 2, side / 2), height(0.5, 3.0);
  std::vector<LedLandmark> leds;
  for (std::size_t k = 0; k < count; ++k) leds.push_back(test::led_at(along(random), along(random), height(random)));
  return leds;
}

TEST(LedNeighbourhood, ListsEveryLedWithinRangeInTheMapsOrder) {
  std::mt19937 random(7);
  const std::vector<LedLandmark> leds = scattered_leds(10'000, 400.0, random);
  const double range = 15.0;
  const LedNeighbourhood neighbourhood(leds, range, 512);
  EXPECT_LT(neighbourhood.densest(), 512u);
  std::vector<int> near;
  near.reserve(neighbourhood.densest());
  std::uniform_real_distribution<double> along(-220.0, 220.0);
  std::size_t listed = 0, within = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d camera(along(random), along(random), 0.5);
    neighbourhood.near(camera, near);
    ASSERT_LE(near.size(), neighbourhood.densest());
    EXPECT_TRUE(std::is_sorted(near.begin(), near.end()));
    for (std::size_t l = 0; l < leds.size(); ++l) {
      if ((leds[l].position - camera).norm() > range) continue;
      ++within;
      EXPECT_TRUE(std::binary_search(near.begin(), near.end(), static_cast<int>(l))) << "LED " << l << " in range";
    }
    listed += near.size();
  }
  EXPECT_GT(within, 200u) << "the trials see LEDs";
  EXPECT_LT(listed, 200u * 600u) << "a trial lists a view's worth of LEDs, not the map";
}

TEST(LedNeighbourhood, AMapDenserThanTheLimitIsRefusedNamingIt) {
  std::mt19937 random(8);
  const std::vector<LedLandmark> leds = scattered_leds(2'000, 20.0, random);
  try {
    const LedNeighbourhood neighbourhood(leds, 15.0, 512);
    FAIL() << "2000 LEDs in 20 x 20 m accepted under a limit of 512";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("led.max_leds_in_range (512)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2000 LED landmarks"), std::string::npos) << e.what();
  }
  EXPECT_EQ(LedNeighbourhood(leds, 15.0, 2000).densest(), 2000u);
}

}  // namespace
}  // namespace irloc::led
