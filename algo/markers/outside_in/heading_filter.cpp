#include "algo/markers/outside_in/heading_filter.hpp"

#include <cmath>
#include <numbers>

namespace irloc::outside_in {
namespace {
constexpr double kUnknownRate = 1.6;  // rad/s: a new track may already be turning at about 90 deg/s
double wrap(double angle) { return std::remainder(angle, 2 * std::numbers::pi); }
}  // namespace

void HeadingFilter::reset(double yaw, double white_variance, double bias_variance) {
  // The fit is yaw + bias + noise: the yaw's error is minus the bias's, plus the noise.
  state_ = {wrap(yaw), 0, 0};
  covariance_ << white_variance + bias_variance, 0, -bias_variance, 0, kUnknownRate * kUnknownRate, 0, -bias_variance, 0,
      bias_variance;
}

void HeadingFilter::turn_by(double turn) { state_(0) = wrap(state_(0) + turn); }

void HeadingFilter::predict(double dt, double travel, double bias_variance) {
  if (dt <= 0) return;
  const double view_change = std::abs(state_(1) * dt) / kBiasTurn + travel / kBiasTravel;
  const double kept = std::exp(-view_change);
  Eigen::Matrix3d transition;
  transition << 1, dt, 0, 0, 1, 0, 0, 0, kept;
  const double q = kAccelerationDensity * kAccelerationDensity;
  Eigen::Matrix3d noise = Eigen::Matrix3d::Zero();
  noise.topLeftCorner<2, 2>() << q * dt * dt * dt / 3, q * dt * dt / 2, q * dt * dt / 2, q * dt;
  noise(2, 2) = (1 - kept * kept) * bias_variance;
  state_ = transition * state_;
  state_(0) = wrap(state_(0));
  covariance_ = transition * covariance_ * transition.transpose() + noise;
}

double HeadingFilter::update(const Eigen::Vector3d& observation, double innovation, double variance) {
  const Eigen::Vector3d cross = covariance_ * observation;
  const Eigen::Vector3d gain = cross / (observation.dot(cross) + variance);
  state_ += gain * innovation;
  state_(0) = wrap(state_(0));
  covariance_ -= gain * cross.transpose();
  covariance_ = 0.5 * (covariance_ + covariance_.transpose()).eval();
  return innovation;
}

double HeadingFilter::update_fit(double measured_yaw, double white_variance, double period) {
  const Eigen::Vector3d observation(1, 0, 1);
  const double innovation = std::remainder(measured_yaw - state_(0) - state_(2), period);
  return update(observation, innovation, white_variance);
}

bool HeadingFilter::update_unbiased(double measured_yaw, double before, double variance, double period) {
  const Eigen::Vector3d observation(1, -before, 0);
  const double innovation = std::remainder(measured_yaw - observation.dot(state_), period);
  if (innovation * innovation > 9 * (observation.dot(covariance_ * observation) + variance)) return false;
  update(observation, innovation, variance);
  return true;
}

}  // namespace irloc::outside_in
