#pragma once
// The heading's branch of a track that began mid-drive (a robot the foreground never saw whole,
// found by the appearance fit wherever it was, perhaps reversing): the box's fits give its heading
// modulo a half turn, and only its travel tells its front, not its first steps (a robot is found
// reversing as often as driving forward), but a long drive mostly one way. The track is not posed
// until the robot has driven kConfirmM along the heading or against it, kRatio times as far one way
// as the other; against it, the heading turns half round. A robot that only turns in place is never
// posed by such a track (docs/outside_in.md, "The appearance fit").
#include <cmath>
#include <utility>

#include <Eigen/Core>

namespace irloc::outside_in {

class TravelBranch {
 public:
  static constexpr double kConfirmM = 1.0;
  static constexpr double kRatio = 4.0;

  // Counts a step of travel (m, on the floor) while the heading was `yaw` (rad). True when the
  // heading must be turned half round (the travel so far is then counted against the new one).
  bool add(const Eigen::Vector2d& step, double yaw) {
    const double along = step.dot(Eigen::Vector2d(std::cos(yaw), std::sin(yaw)));
    (along >= 0 ? forward_m_ : backward_m_) += std::abs(along);
    if (confirmed_) return false;
    const bool turn = backward_m_ >= kConfirmM && backward_m_ >= kRatio * forward_m_;
    if (turn) std::swap(forward_m_, backward_m_);
    confirmed_ = forward_m_ >= kConfirmM && forward_m_ >= kRatio * backward_m_;
    return turn;
  }
  // The branch is known otherwise (the track took its last pose's on reacquiring the robot).
  void confirm() { confirmed_ = true; }
  bool confirmed() const { return confirmed_; }

 private:
  double forward_m_ = 0, backward_m_ = 0;
  bool confirmed_ = false;
};

}  // namespace irloc::outside_in
