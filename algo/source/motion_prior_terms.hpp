#pragma once
// A prior on the motion within a frame (MotionPrior: the fastest robot's, or the motion before a
// gap) as terms of a Gauss-Newton fit whose last three parameters are that motion (velocity x, y
// in the heading frame, then the yaw rate), so that the fit is the MAP estimate. `weight` puts the
// prior in the fit's units: the variance of one of its residuals (pixels squared for a
// reprojection fit, metres squared for the square's tape). The joint pose-and-motion fit
// (pose_motion_fit.hpp) and the square's tape motion fit share them.

#include <Eigen/Core>

#include "algo/source/source_input.hpp"

namespace irloc {

// The prior's information (inverse variances) on the forward and the sideways velocity (x, y of
// the heading frame) and on the yaw rate.
inline Eigen::Vector3d motion_prior_information(const MotionPrior& prior) {
  return {1 / (prior.velocity_sigma * prior.velocity_sigma), 1 / (prior.side_velocity_sigma * prior.side_velocity_sigma),
          1 / (prior.yaw_rate_sigma * prior.yaw_rate_sigma)};
}

// Adds the prior at `weight` to a step's normal system (its diagonal's last three) and to its
// right-hand side `gradient` (the step solves system * step = gradient, gradient = -J^T r): the
// pull toward the prior's mean from `motion`, the current state's.
template <typename System, typename Gradient>
void add_motion_prior(const MotionPrior& prior, const FrameMotion& motion, double weight, System& system,
                      Gradient& gradient) {
  const Eigen::Vector3d information = weight * motion_prior_information(prior);
  system.diagonal().tail(3) += information;
  const Eigen::Vector3d from_mean(motion.velocity.x() - prior.mean.velocity.x(),
                                  motion.velocity.y() - prior.mean.velocity.y(), motion.yaw_rate - prior.mean.yaw_rate);
  gradient.tail(3) -= information.cwiseProduct(from_mean);
}

}  // namespace irloc
