#pragma once
// The tracked robot's heading and turn rate: a Kalman filter on (yaw, yaw rate, fit bias) with a
// constant turn rate between frames (white angular acceleration). The box fit's heading alone
// fails where the robot turns through the camera's line of sight: there the silhouette and its
// mirror image are within the mask's noise, each fit lands a few to 15 degrees off, on either
// side, and a track that followed the fits lagged, then took the mirror branch (heading 90-180
// degrees off while the robot turned in place). The filter carries the turn through: its
// prediction picks the fit's branch (modulo the box's symmetry turn) and weighs it by the fit's
// variance.
//
// A fit's error is mostly systematic: the mask's edges are off by about a pixel the same way as
// long as the robot shows the camera the same view. Taken as white noise, the fits of a robot at
// rest would average it away on paper, and the filter would claim a heading several times truer
// than it is (docs/outside_in.md, step 5, has the measurement). So the bias is a state: each fit
// measures yaw + bias; the bias keeps its value while the view stays and is drawn anew as the
// robot turns or drives (a first-order Markov process in the view's change). A heading from
// elsewhere (the direction of travel) measures the yaw alone and so also tells the bias.
#include <Eigen/Core>

namespace irloc::outside_in {

class HeadingFilter {
 public:
  // Angular acceleration the filter allows, rad/s^2 per sqrt(s): a robot starts or stops a turn
  // in place of 60 deg/s within about 3 frames at 10 fps.
  static constexpr double kAccelerationDensity = 0.7;
  // The view's change over which a fit's bias decorrelates (to 1/e): a turn of this much (rad) ...
  static constexpr double kBiasTurn = 0.26;
  // ... or a drive of this far (m).
  static constexpr double kBiasTravel = 0.5;

  // Starts from a fit's heading yaw (rad): white_variance its own noise, bias_variance (rad^2)
  // that of its systematic error; turn rate 0 but unknown.
  void reset(double yaw, double white_variance, double bias_variance);
  // Adds a turn (rad) to the heading and nothing to its uncertainty (the box's symmetry resolved).
  void turn_by(double turn);
  // Moves the state dt seconds on; the robot drove `travel` m meanwhile. bias_variance: the
  // systematic error's variance of fits in the new view.
  void predict(double dt, double travel, double bias_variance);
  // A fit's heading, known only modulo `period` (the box's symmetry turn): yaw + bias + white
  // noise of white_variance. The branch nearest the prediction is taken. Returns the innovation
  // (rad, on that branch).
  double update_fit(double measured_yaw, double white_variance, double period);
  // The heading `before` seconds ago, measured without the fit's bias (modulo period, variance in
  // rad^2): through the turn rate it also tells the rate. Applied only when the innovation is
  // within 3 sigma (a robot that drives sideways, a track's jump); returns whether it was.
  bool update_unbiased(double measured_yaw, double before, double variance, double period);

  double yaw() const { return state_(0); }        // rad, in (-pi, pi]
  double rate() const { return state_(1); }       // rad/s
  double bias() const { return state_(2); }       // rad: the fits' current systematic error
  double yaw_variance() const { return covariance_(0, 0); }
  double rate_variance() const { return covariance_(1, 1); }

 private:
  double update(const Eigen::Vector3d& observation, double innovation, double variance);

  Eigen::Vector3d state_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance_ = Eigen::Matrix3d::Identity();
};

}  // namespace irloc::outside_in
