// The heading filter's two motion models on drives whose truth is known: fits that carry a
// systematic error and noise, and travel lines that measure the heading free of it.
#include "algo/markers/outside_in/heading_filter.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace irloc::outside_in {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kDt = 0.1;           // 10 fps
constexpr double kSpeed = 0.47;       // m/s
constexpr double kFitBias = 4 * kDeg;       // the mask's systematic error: the same while the view is
constexpr double kFitNoise = 1 * kDeg;
constexpr double kLineNoise = 3 * kDeg;     // a travel line's error, 1 sigma
constexpr double kLineAge = 0.15;           // s: the line tells the heading this long ago

double wrap(double angle) { return std::remainder(angle, 2 * std::numbers::pi); }

class SimulatedRobot {
 public:
  explicit SimulatedRobot(unsigned seed) : rng_(seed) {
    filter.reset(fit(), kFitNoise * kFitNoise, kFitBias * kFitBias);
  }
  // One frame: the robot turned by `turn` (rad) and drove `travel` (m); a fit, and a travel line
  // while it drives.
  void step(double turn, double travel) {
    yaw_history_[0] = yaw_history_[1];
    yaw_history_[1] = yaw;
    yaw = wrap(yaw + turn);
    filter.predict(kDt, travel, travel < HeadingFilter::kRestSpeed * kDt, kFitBias * kFitBias);
    filter.update_fit(fit(), kFitNoise * kFitNoise, std::numbers::pi);
    // The line through the last positions tells the heading of about kLineAge ago.
    if (travel > 0) filter.update_unbiased(yaw_history_[0] + noise_(rng_) * kLineNoise, kLineAge, kLineNoise * kLineNoise,
                                           std::numbers::pi);
  }
  double error() const { return wrap(filter.yaw() - yaw); }
  double sigma() const { return std::sqrt(filter.yaw_variance()); }

  HeadingFilter filter;
  double yaw = 0.3;

 private:
  double fit() { return yaw + kFitBias + noise_(rng_) * kFitNoise; }
  std::mt19937 rng_;
  std::normal_distribution<double> noise_{0, 1};
  double yaw_history_[2] = {0.3, 0.3};
};

// Driving straight, the steady model keeps what the travel lines tell: the heading is certain
// (one model sized for a turn that may start any frame stayed at about 6 degrees), and right.
TEST(HeadingFilter, DrivingStraightTheTravelLinesMakeTheHeadingCertain) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    SimulatedRobot two_models(seed);
    for (int frame = 0; frame < 30; ++frame) two_models.step(0, kSpeed * kDt);
    EXPECT_LT(two_models.sigma(), 2.6 * kDeg) << "seed " << seed;
    EXPECT_LT(std::abs(two_models.error()), 3 * two_models.sigma()) << "seed " << seed;
    EXPECT_LT(two_models.filter.turning_probability(), 0.5) << "seed " << seed;
  }
}

// A robot that drives, stops and at once turns in place at 60 deg/s for a half turn, then stands:
// the filter never claims a heading (sigma under 5 degrees) that is 10 degrees off, switches to
// the turning model within 3 frames, and after the turn knows the heading again.
TEST(HeadingFilter, ATurnInPlaceRightAfterADriveIsNeverClaimedWrong) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    SimulatedRobot robot(seed);
    for (int frame = 0; frame < 30; ++frame) robot.step(0, kSpeed * kDt);
    for (int frame = 0; frame < 30; ++frame) {
      robot.step(6 * kDeg, 0);
      if (robot.sigma() < 5 * kDeg) {
        EXPECT_LT(std::abs(robot.error()), 10 * kDeg) << "seed " << seed << " turn frame " << frame;
      }
      if (frame >= 2) {
        EXPECT_GT(robot.filter.turning_probability(), 0.5) << "seed " << seed << " turn frame " << frame;
      }
    }
    for (int frame = 0; frame < 20; ++frame) {
      robot.step(0, 0);
      if (robot.sigma() < 5 * kDeg) {
        EXPECT_LT(std::abs(robot.error()), 10 * kDeg) << "seed " << seed << " rest frame " << frame;
      }
    }
    EXPECT_LT(std::abs(robot.error()), 3 * robot.sigma()) << "seed " << seed;
  }
}

}  // namespace
}  // namespace irloc::outside_in
