#include "algo/outside_in/heading_filter.hpp"

#include <cmath>
#include <numbers>

namespace irloc {
namespace {
constexpr double kUnknownRate = 1.6;  // rad/s: a new track may already be turning at about 90 deg/s
double wrap(double angle) { return std::remainder(angle, 2 * std::numbers::pi); }
}  // namespace

void HeadingFilter::reset(double yaw, double yaw_variance) {
  state_ = {wrap(yaw), 0};
  covariance_ << yaw_variance, 0, 0, kUnknownRate * kUnknownRate;
}

void HeadingFilter::predict(double dt) {
  if (dt <= 0) return;
  Eigen::Matrix2d transition;
  transition << 1, dt, 0, 1;
  const double q = kAccelerationDensity * kAccelerationDensity;
  Eigen::Matrix2d noise;
  noise << q * dt * dt * dt / 3, q * dt * dt / 2, q * dt * dt / 2, q * dt;
  state_ = transition * state_;
  state_(0) = wrap(state_(0));
  covariance_ = transition * covariance_ * transition.transpose() + noise;
}

double HeadingFilter::update(double measured_yaw, double variance, double period) {
  const double innovation = std::remainder(measured_yaw - state_(0), period);
  const double innovation_variance = covariance_(0, 0) + variance;
  const Eigen::Vector2d gain = covariance_.col(0) / innovation_variance;
  state_ += gain * innovation;
  state_(0) = wrap(state_(0));
  covariance_ -= gain * covariance_.row(0);
  return innovation;
}

}  // namespace irloc
