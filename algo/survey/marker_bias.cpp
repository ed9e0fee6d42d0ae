#include "algo/survey/marker_bias.hpp"

#include <algorithm>

namespace irloc::survey {

MarkerBias::Contribution MarkerBias::contribution(const DotSums& dot) {
  Contribution result;
  if (dot.count < 2) return result;
  const Eigen::Vector2d sum = dot.sum.cast<double>();
  const double n = dot.count;
  result.within = static_cast<double>(dot.squares) - sum.squaredNorm() / n;
  result.mean_squares = sum.squaredNorm() / (n * n);
  result.inverse_count = 2.0 / n;
  result.degrees = 2 * (dot.count - 1);
  result.dots = 1;
  return result;
}

void MarkerBias::pool(const Contribution& contribution, double sign) {
  within_ += sign * contribution.within;
  mean_squares_ += sign * contribution.mean_squares;
  inverse_counts_ += sign * contribution.inverse_count;
  within_degrees_ += static_cast<int>(sign) * contribution.degrees;
  pooled_dots_ += static_cast<int>(sign) * contribution.dots;
}

void MarkerBias::add(int node, const MarkerSighting& sighting, const Eigen::Matrix2d& level_from_camera_2d) {
  auto& cells = dots_[static_cast<std::size_t>(node)];
  for (int cell = 0; cell < dot::kCellCount; ++cell) {
    if ((sighting.cells >> cell & 1u) == 0) continue;
    DotSums& dot = cells[static_cast<std::size_t>(cell)];
    pool(contribution(dot), -1);
    const Eigen::Vector2d residual = level_from_camera_2d * sighting.residuals.col(cell);
    dot.sum += residual.cast<float>();
    dot.squares += static_cast<float>(residual.squaredNorm());
    ++dot.count;
    pool(contribution(dot), 1);
  }
}

double MarkerBias::share() const {
  if (within_degrees_ <= 0 || pooled_dots_ == 0) return 0;
  const double noise = within_ / within_degrees_;  // per axis
  if (noise <= 0) return 0;
  // Per axis: a dot's mean holds its fixed error plus noise / n.
  const double fixed = (mean_squares_ - noise * inverse_counts_) / (2.0 * pooled_dots_);
  return std::clamp(fixed / noise, 0.0, 1.0);
}

}  // namespace irloc::survey
