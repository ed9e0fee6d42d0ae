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
//
// Two motion models, mixed as an interacting multiple model (Blom & Bar-Shalom 1988): steady (a
// robot that drives straight, on a curve or stands: little angular acceleration) and turning (one
// that starts or stops a turn in place, within a few frames). One model sized for turns in place
// keeps a driving robot's turn-rate sigma so wide that the travel line, which tells the heading of
// 0.2 s ago, cannot make the heading now certain. Each measurement weighs the models by how well
// they predicted it; the heading and its variance are the mixture's (its spread between the models
// included), so while the evidence does not yet tell a turn from noise the variance says so.
#include <array>

#include <Eigen/Core>

namespace irloc::outside_in {

class HeadingFilter {
 public:
  // White angular acceleration of each motion model, rad/s^2 per sqrt(s): a robot driving
  // straight, on a curve or standing (enough to follow a curve whose turn rate grows from 7 to
  // 55 deg/s), and one starting or stopping a turn (a turn in place of 60 deg/s within about 3
  // frames at 10 fps).
  static constexpr double kSteadyAcceleration = 0.2;
  static constexpr double kTurnAcceleration = 0.7;
  // The view's change over which a fit's bias decorrelates (to 1/e): a turn of this much (rad) ...
  static constexpr double kBiasTurn = 0.26;
  // ... or a drive of this far (m).
  static constexpr double kBiasTravel = 0.5;
  // How often the robot switches between the motion models, 1/s ...
  static constexpr double kSwitchRate = 0.5;
  // ... except that a robot at rest (slower than kRestSpeed, m/s) may start a turn
  // in place any frame: from rest, the steady model switches to turning this often (1/s), so a
  // robot that stops and turns at once is not taken as steady through the turn's first frames.
  static constexpr double kRestSpeed = 0.15;
  static constexpr double kTurnStartRateAtRest = 5;
  // A turn starts with a step of the turn rate (rad/s, 1 sigma: a turn in place of up to about
  // 60 deg/s, reached within a frame): the steady estimate enters the turning model with this
  // much more rate uncertainty, which white angular acceleration alone gives only frames later.
  static constexpr double kTurnStartRate = 1.0;

  // Starts from a fit's heading yaw (rad): white_variance its own noise, bias_variance (rad^2)
  // that of its systematic error; turn rate 0 but unknown; either motion model equally likely.
  void reset(double yaw, double white_variance, double bias_variance);
  // Adds a turn (rad) to the heading and nothing to its uncertainty (the box's symmetry resolved).
  void turn_by(double turn);
  // Moves the state dt seconds on; the robot drove `travel` m meanwhile and is `at_rest` (slower
  // than kRestSpeed). bias_variance: the systematic error's variance of fits in the new view.
  void predict(double dt, double travel, bool at_rest, double bias_variance);
  // A fit's heading, known only modulo `period` (the box's symmetry turn): yaw + bias + white
  // noise of white_variance. Each model takes the branch nearest its prediction.
  void update_fit(double measured_yaw, double white_variance, double period);
  // The heading `before` seconds ago, measured without the fit's bias (modulo period, variance in
  // rad^2): through the turn rate it also tells the rate. Applied only when the innovation is
  // within 3 sigma of the mixture (a robot that drives sideways, a track's jump); returns whether
  // it was.
  bool update_unbiased(double measured_yaw, double before, double variance, double period);

  double yaw() const { return mixture_.state(0); }        // rad, in (-pi, pi]
  double rate() const { return mixture_.state(1); }       // rad/s
  double bias() const { return mixture_.state(2); }       // rad: the fits' current systematic error
  double yaw_variance() const { return mixture_.covariance(0, 0); }
  double rate_variance() const { return mixture_.covariance(1, 1); }
  double turning_probability() const { return models_[1].probability; }

 private:
  struct Model {
    Eigen::Vector3d state = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
    double probability = 0.5;
  };
  // Each model's prior for the next step: the models' estimates mixed by the switch
  // probabilities over dt (at_rest: the robot did not drive meanwhile).
  void mix(double dt, bool at_rest);
  // Updates every model with observation . state + noise(variance) = measured (modulo period) and
  // reweighs the models by the likelihood of their innovations.
  void update(const Eigen::Vector3d& observation, double measured, double variance, double period);
  // The mixture (weights summing to 1) as one Gaussian: its mean, yaw differences taken about
  // `reference` (one of the models' states) the short way round, and its covariance with the
  // models' spread about that mean.
  static Model moment_matched(const std::array<Model, 2>& models, const std::array<double, 2>& weights,
                              const Eigen::Vector3d& reference);
  // mixture_ from the models and their probabilities.
  void combine();

  std::array<Model, 2> models_{};  // steady, turning
  Model mixture_;
};

}  // namespace irloc::outside_in
