#include "algo/survey/marker_candidate.hpp"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "algo/geometry/pose.hpp"

namespace irloc::survey {

CeilingPose MarkerCandidate::mean() const {
  CeilingPose result = reference + information.ldlt().solve(information_offset);
  result[3] = wrap_angle(result[3]);
  return result;
}

CeilingCovariance MarkerCandidate::covariance() const { return information.inverse() + anchor_covariance; }

void MarkerCandidate::add_sighting(const CeilingPose& pose, const CeilingCovariance& own, const CeilingCovariance& anchor,
                                   const Eigen::Vector2d& robot, int anchor_node, const RelativeSighting& relative) {
  const CeilingCovariance sighting_information = (own + anchor).inverse();
  const CeilingPose offset = pose_difference(pose, reference);
  information += sighting_information;
  information_offset += sighting_information * offset;
  weighted_squares += offset.dot(sighting_information * offset);
  if (anchor.trace() < anchor_covariance.trace()) anchor_covariance = anchor;
  view_min = view_min.cwiseMin(robot);
  view_max = view_max.cwiseMax(robot);
  kept.push_back({anchor_node, relative});
  ++sightings;
}

void MarkerCandidate::add_other_sighting(const CeilingPose& pose) {
  if (other_sightings == 0) other_mean = pose;
  ++other_sightings;
  other_mean += pose_difference(pose, other_mean) / other_sightings;
  other_mean[3] = wrap_angle(other_mean[3]);
}

CeilingCovariance rotated_covariance(const CeilingPose& a, const CeilingCovariance& relative) {
  CeilingJacobian turn = CeilingJacobian::Identity();
  const double c = std::cos(a[3]), s = std::sin(a[3]);
  turn.block<2, 2>(0, 0) << c, -s, s, c;
  return turn * relative * turn.transpose();
}

CeilingCovariance anchor_share(const CeilingPose& a, const CeilingPose& a_to_b, const CeilingCovariance& anchor) {
  CeilingJacobian lever = CeilingJacobian::Identity();
  const double c = std::cos(a[3]), s = std::sin(a[3]);
  lever(0, 3) = -s * a_to_b.x() - c * a_to_b.y();
  lever(1, 3) = c * a_to_b.x() - s * a_to_b.y();
  return lever * anchor * lever.transpose();
}

}  // namespace irloc::survey
