#include "algo/markers/outside_in/heading_filter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace irloc::outside_in {
namespace {
constexpr double kUnknownRate = 1.6;  // rad/s: a new track may already be turning at about 90 deg/s
double wrap(double angle) { return std::remainder(angle, 2 * std::numbers::pi); }
constexpr double kModelAcceleration[2] = {HeadingFilter::kSteadyAcceleration, HeadingFilter::kTurnAcceleration};

// a - b with the yaw (component 0) taken the short way round.
Eigen::Vector3d difference(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::Vector3d d = a - b;
  d(0) = wrap(d(0));
  return d;
}
}  // namespace

void HeadingFilter::reset(double yaw, double white_variance, double bias_variance) {
  // The fit is yaw + bias + noise: the yaw's error is minus the bias's, plus the noise.
  Model start;
  start.state = {wrap(yaw), 0, 0};
  start.covariance << white_variance + bias_variance, 0, -bias_variance, 0, kUnknownRate * kUnknownRate, 0,
      -bias_variance, 0, bias_variance;
  models_ = {start, start};
  combine();
}

void HeadingFilter::turn_by(double turn) {
  for (Model& model : models_) model.state(0) = wrap(model.state(0) + turn);
  mixture_.state(0) = wrap(mixture_.state(0) + turn);
}

void HeadingFilter::mix(double dt, bool at_rest) {
  const double switched = 1 - std::exp(-kSwitchRate * dt);
  const double starts_turning = at_rest ? 1 - std::exp(-kTurnStartRateAtRest * dt) : switched;
  // switch_probability[i][j]: from model i to model j (0 steady, 1 turning).
  const double switch_probability[2][2] = {{1 - starts_turning, starts_turning}, {switched, 1 - switched}};
  std::array<Model, 2> mixed = models_;
  for (std::size_t j = 0; j < models_.size(); ++j) {
    std::array<double, 2> weights;
    double total = 0;
    for (std::size_t i = 0; i < models_.size(); ++i) {
      weights[i] = switch_probability[i][j] * models_[i].probability;
      total += weights[i];
    }
    for (double& weight : weights) weight /= total;
    mixed[j] = moment_matched(models_, weights, models_[j].state);
    if (j == 1) mixed[j].covariance(1, 1) += weights[0] * kTurnStartRate * kTurnStartRate;  // a turn starting
    mixed[j].probability = total;
  }
  models_ = mixed;
}

void HeadingFilter::predict(double dt, double travel, bool at_rest, double bias_variance) {
  if (dt <= 0) return;
  mix(dt, at_rest);
  for (std::size_t j = 0; j < models_.size(); ++j) {
    Model& model = models_[j];
    const double view_change = std::abs(model.state(1) * dt) / kBiasTurn + travel / kBiasTravel;
    const double kept = std::exp(-view_change);
    Eigen::Matrix3d transition;
    transition << 1, dt, 0, 0, 1, 0, 0, 0, kept;
    const double q = kModelAcceleration[j] * kModelAcceleration[j];
    Eigen::Matrix3d noise = Eigen::Matrix3d::Zero();
    noise.topLeftCorner<2, 2>() << q * dt * dt * dt / 3, q * dt * dt / 2, q * dt * dt / 2, q * dt;
    noise(2, 2) = (1 - kept * kept) * bias_variance;
    model.state = transition * model.state;
    model.state(0) = wrap(model.state(0));
    model.covariance = transition * model.covariance * transition.transpose() + noise;
  }
  combine();
}

void HeadingFilter::update(const Eigen::Vector3d& observation, double measured, double variance, double period) {
  double log_likelihood[2];
  for (std::size_t j = 0; j < models_.size(); ++j) {
    Model& model = models_[j];
    const double innovation = std::remainder(measured - observation.dot(model.state), period);
    const Eigen::Vector3d cross = model.covariance * observation;
    const double innovation_variance = observation.dot(cross) + variance;
    const Eigen::Vector3d gain = cross / innovation_variance;
    model.state += gain * innovation;
    model.state(0) = wrap(model.state(0));
    model.covariance -= gain * cross.transpose();
    model.covariance = 0.5 * (model.covariance + model.covariance.transpose()).eval();
    log_likelihood[j] = -0.5 * (innovation * innovation / innovation_variance + std::log(innovation_variance));
  }
  // Reweighed relative to the likelier model: no underflow however far off the other one is.
  const double best = std::max(log_likelihood[0], log_likelihood[1]);
  double total = 0;
  for (std::size_t j = 0; j < models_.size(); ++j) {
    models_[j].probability *= std::exp(log_likelihood[j] - best);
    total += models_[j].probability;
  }
  for (Model& model : models_) model.probability /= total;
  combine();
}

HeadingFilter::Model HeadingFilter::moment_matched(const std::array<Model, 2>& models, const std::array<double, 2>& weights,
                                                   const Eigen::Vector3d& reference) {
  Model matched;
  matched.state = reference;
  for (std::size_t i = 0; i < models.size(); ++i) matched.state += weights[i] * difference(models[i].state, reference);
  matched.state(0) = wrap(matched.state(0));
  matched.covariance.setZero();
  for (std::size_t i = 0; i < models.size(); ++i) {
    const Eigen::Vector3d d = difference(models[i].state, matched.state);
    matched.covariance += weights[i] * (models[i].covariance + d * d.transpose());
  }
  return matched;
}

void HeadingFilter::combine() {
  const Model matched = moment_matched(models_, {models_[0].probability, models_[1].probability}, models_[0].state);
  mixture_.state = matched.state;
  mixture_.covariance = matched.covariance;
}

void HeadingFilter::update_fit(double measured_yaw, double white_variance, double period) {
  update(Eigen::Vector3d(1, 0, 1), measured_yaw, white_variance, period);
}

bool HeadingFilter::update_unbiased(double measured_yaw, double before, double variance, double period) {
  const Eigen::Vector3d observation(1, -before, 0);
  const double innovation = std::remainder(measured_yaw - observation.dot(mixture_.state), period);
  if (innovation * innovation > 9 * (observation.dot(mixture_.covariance * observation) + variance)) return false;
  update(observation, measured_yaw, variance, period);
  return true;
}

}  // namespace irloc::outside_in
