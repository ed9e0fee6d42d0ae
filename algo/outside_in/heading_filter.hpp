#pragma once
// The tracked robot's heading and turn rate: a Kalman filter on (yaw, yaw rate) with a constant
// turn rate between frames (white angular acceleration). The box fit's heading alone fails
// where the robot turns through the camera's line of sight: there the silhouette and its mirror
// image are within the mask's noise, each fit lands a few to 15 degrees off, on either side, and
// a track that followed the fits lagged, then took the mirror branch (heading 90-180 degrees
// off while the robot turned in place). The filter carries the turn through: its prediction
// picks the fit's branch (modulo the box's symmetry turn) and weighs it by the fit's variance.
#include <Eigen/Core>

namespace irloc {

class HeadingFilter {
 public:
  // Angular acceleration the filter allows, rad/s^2 per sqrt(s): a robot starts or stops a turn
  // in place of 60 deg/s within about 3 frames at 10 fps.
  static constexpr double kAccelerationDensity = 0.7;

  // Starts at yaw (rad) known to within yaw_variance (rad^2), turn rate 0 but unknown.
  void reset(double yaw, double yaw_variance);
  // Moves the state dt seconds on.
  void predict(double dt);
  // A measured heading, known only modulo `period` (the box's symmetry turn), with its variance:
  // the branch nearest the prediction is taken. Returns the innovation (rad, on that branch).
  double update(double measured_yaw, double variance, double period);

  double yaw() const { return state_(0); }        // rad, in (-pi, pi]
  double rate() const { return state_(1); }       // rad/s
  double yaw_variance() const { return covariance_(0, 0); }

 private:
  Eigen::Vector2d state_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance_ = Eigen::Matrix2d::Identity();
};

}  // namespace irloc
