#include "algo/survey/marker_bias.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

namespace irloc::survey {

MarkerBias::Contribution MarkerBias::contribution(const DotSums& dot) {
  Contribution result;
  if (dot.count < 2) return result;
  const Eigen::Vector2d sum = dot.sum.cast<double>();
  const double n = dot.count;
  Eigen::Matrix2d squares;
  squares << dot.squares[0], dot.squares[2], dot.squares[2], dot.squares[1];
  result.within = squares - sum * sum.transpose() / n;
  result.mean_squares = sum * sum.transpose() / (n * n);
  result.inverse_count = 1.0 / n;
  result.degrees = dot.count - 1;
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
  const auto n = static_cast<std::size_t>(node);
  const Eigen::Vector2f heading = level_from_camera_2d.col(0).cast<float>();
  if (first_heading_[n].isZero()) first_heading_[n] = heading;
  // The way back sees the marker's fixed error with both image axes turned: fold it back.
  const float fold = first_heading_[n].dot(heading) >= 0 ? 1.0f : -1.0f;
  auto& cells = dots_[n];
  for (int cell = 0; cell < dot::kCellCount; ++cell) {
    if ((sighting.cells >> cell & 1u) == 0) continue;
    DotSums& dot = cells[static_cast<std::size_t>(cell)];
    pool(contribution(dot), -1);
    const Eigen::Vector2f residual = fold * sighting.residuals.col(cell).cast<float>();
    dot.sum += residual;
    dot.squares += Eigen::Vector3f(residual.x() * residual.x(), residual.y() * residual.y(), residual.x() * residual.y());
    ++dot.count;
    pool(contribution(dot), 1);
  }
}

Eigen::Matrix2d MarkerBias::fixed_covariance() const {
  if (within_degrees_ <= 0 || pooled_dots_ == 0) return Eigen::Matrix2d::Zero();
  const Eigen::Matrix2d noise = within_ / within_degrees_;
  const double pixel_variance = 0.5 * noise.trace();
  if (pixel_variance <= 0) return Eigen::Matrix2d::Zero();
  // A dot's mean holds its fixed error plus noise / n.
  const Eigen::Matrix2d fixed = (mean_squares_ - noise * inverse_counts_) / pooled_dots_;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(fixed);
  const Eigen::Vector2d variances = axes.eigenvalues().cwiseMax(0.0).cwiseMin(pixel_variance);
  return axes.eigenvectors() * variances.asDiagonal() * axes.eigenvectors().transpose();
}

}  // namespace irloc::survey
