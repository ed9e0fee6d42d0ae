#include "algo/markers/dot/grey_level_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace irloc::dot {
namespace {

// A component's weighted density, with sigma floored so a degenerate fit cannot divide by zero.
double weighted_density(const GreyLevelComponent& c, double x) {
  const double sigma = std::max(c.sigma, 1e-3);
  const double z = (x - c.mean) / sigma;
  return c.weight * std::exp(-0.5 * z * z) / (sigma * std::sqrt(2 * std::numbers::pi));
}

}  // namespace

double dot_posterior(const GreyLevelModel& model, double intensity) {
  // Two Gaussians of unequal width cross twice, so the raw posterior turns back in one tail. The
  // evidence is made monotonic by clamping the intensity to [clutter mean, dot mean], narrowed to
  // the turning point of the log-ratio (a quadratic) when it lies inside.
  double low = model.clutter.mean;
  double high = model.dot.mean;
  const double inv_dot = 1.0 / (model.dot.sigma * model.dot.sigma);
  const double inv_clutter = 1.0 / (model.clutter.sigma * model.clutter.sigma);
  if (inv_clutter != inv_dot) {
    const double turning = (model.clutter.mean * inv_clutter - model.dot.mean * inv_dot) / (inv_clutter - inv_dot);
    if (inv_clutter > inv_dot) low = std::max(low, turning);  // log-ratio convex: a minimum
    else high = std::min(high, turning);                     // concave: a maximum
  }
  const double x = low < high ? std::clamp(intensity, low, high) : intensity;
  const double dot = weighted_density(model.dot, x);
  const double clutter = weighted_density(model.clutter, x);
  // Far beyond both means both densities underflow; the brighter side then belongs to dots.
  if (dot + clutter <= 0) return x > model.clutter.mean ? 1.0 : 0.0;
  return dot / (dot + clutter);
}

GreyLevelModel fit_grey_level_model(std::span<const double> intensities, const GreyLevelModel& start, int iterations) {
  if (intensities.size() < 4) return start;
  GreyLevelModel model = start;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    double n_dot = 0, sum_dot = 0, sq_dot = 0, n_clutter = 0, sum_clutter = 0, sq_clutter = 0;
    for (const double x : intensities) {
      const double d = weighted_density(model.dot, x);
      const double c = weighted_density(model.clutter, x);
      const double r = d + c > 0 ? d / (d + c) : (x > model.clutter.mean ? 1.0 : 0.0);
      n_dot += r;
      sum_dot += r * x;
      sq_dot += r * x * x;
      n_clutter += 1 - r;
      sum_clutter += (1 - r) * x;
      sq_clutter += (1 - r) * x * x;
    }
    const auto update = [](GreyLevelComponent& c, double n, double sum, double sq, double total) {
      if (n < 1e-9) return;
      c.weight = n / total;
      c.mean = sum / n;
      c.sigma = std::sqrt(std::max(sq / n - c.mean * c.mean, 1.0));  // at least one grey level
    };
    const auto total = static_cast<double>(intensities.size());
    update(model.dot, n_dot, sum_dot, sq_dot, total);
    update(model.clutter, n_clutter, sum_clutter, sq_clutter, total);
  }
  if (model.dot.mean < model.clutter.mean) std::swap(model.dot, model.clutter);
  return model;
}

}  // namespace irloc::dot
