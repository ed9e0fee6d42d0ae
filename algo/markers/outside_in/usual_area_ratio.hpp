#pragma once
// The robot's own usual blob area / fitted silhouette area in this room, learned from its
// confident poses, and the test that a blob holds more than the robot: merged with a sun patch's
// ghost or a mover, whose fit is pulled toward it (10-30 degrees, several cm). What the robot
// alone measures is a property of the room (its mask against the box model: the opening, the
// floor reference's error, the renderer or the lens), 0.82-1.03 on bench_outside_goal's rooms and
// steady within one room (a spread of about 0.005), so a fixed limit sits on some room's edge; this
// limit follows the room.
#include <algorithm>
#include <cmath>

namespace irloc::outside_in {

class UsualAreaRatio {
 public:
  // Ratios learned before the test applies: the mean and spread of fewer are not the room's.
  static constexpr int kLearnedAfter = 16;
  // Exponential forgetting over about this many confident poses: the ratio drifts with the view.
  static constexpr double kWindow = 32;
  // A merge exceeds the usual mean by more than this many spreads, and by at least kMinExcess
  // (a few pixels of mask on a small far robot; the steadiest rooms' spread is 0.001).
  static constexpr double kSpreads = 4;
  static constexpr double kMinExcess = 0.02;

  // A confident pose's area ratio.
  void learn(double ratio) {
    const double step = 1 / std::min(static_cast<double>(count_ + 1), kWindow);
    const double offset = ratio - mean_;
    mean_ += step * offset;
    variance_ = (1 - step) * (variance_ + step * offset * offset);
    ++count_;
  }
  bool learned() const { return count_ >= kLearnedAfter; }
  // Above the robot's usual ratio by more than its spread allows: the blob holds something else.
  bool merged(double ratio) const {
    return learned() && ratio > mean_ + std::max(kSpreads * std::sqrt(variance_), kMinExcess);
  }
  double mean() const { return mean_; }
  double spread() const { return std::sqrt(variance_); }
  void forget() { *this = UsualAreaRatio{}; }

 private:
  double mean_ = 0, variance_ = 0;
  int count_ = 0;
};

}  // namespace irloc::outside_in
