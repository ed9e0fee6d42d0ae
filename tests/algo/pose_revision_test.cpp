// The gate a revision of a pose passes (pose_revision.hpp): within the chi-square bound of 3
// degrees of freedom under both covariances, the yaw difference taken on the circle.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "algo/core/chi_square.hpp"
#include "algo/pipeline/pose_revision.hpp"

namespace irloc {
namespace {

PoseEstimate level_pose(double x, double y, double yaw, double position_sigma, double yaw_sigma) {
  PoseEstimate pose;
  pose.ok = true;
  pose.x = x;
  pose.y = y;
  pose.yaw = yaw;
  pose.covariance(0, 0) = pose.covariance(1, 1) = position_sigma * position_sigma;
  pose.covariance(5, 5) = yaw_sigma * yaw_sigma;
  return pose;
}

// The Mahalanobis distance at which the gate closes, in standard deviations along one axis.
double gate_sigmas() { return std::sqrt(chi_square_quantile_at(3, kRevisionGateNormalQuantile)); }

TEST(PoseRevision, AgreesWithinTheGateAlongEachAxisAndNotBeyond) {
  // First pose 1 mm and 0.1 degree; the revision taken from a pose of 1 mm and 0.1 degree too:
  // the difference's sigma is sqrt(2) of each.
  const double position_sigma = 0.001, yaw_sigma = 0.1 * std::numbers::pi / 180;
  const PoseEstimate first = level_pose(1.0, 2.0, 0.5, position_sigma, yaw_sigma);
  const PoseCovariance revised_from = first.covariance;
  const double along = std::sqrt(2.0) * gate_sigmas();
  ASSERT_GT(gate_sigmas(), 3.5);
  ASSERT_LT(gate_sigmas(), 4.5);
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      const double sigma = axis == 2 ? yaw_sigma : position_sigma;
      for (const double fraction : {0.95, 1.05}) {
        PoseEstimate revised = first;
        const double step = side * fraction * along * sigma;
        (axis == 0 ? revised.x : axis == 1 ? revised.y : revised.yaw) += step;
        EXPECT_EQ(revision_agrees(first, revised, revised_from), fraction < 1)
            << "axis " << axis << ", " << fraction << " of the gate, side " << side;
      }
    }
  }
}

TEST(PoseRevision, TakesTheYawDifferenceOnTheCircle) {
  const double yaw_sigma = 0.01;
  const PoseEstimate first = level_pose(0, 0, std::numbers::pi - 0.005, 0.001, yaw_sigma);
  PoseEstimate revised = first;
  revised.yaw = -std::numbers::pi + 0.005;  // 0.01 rad on from the first, across the cut
  EXPECT_TRUE(revision_agrees(first, revised, first.covariance));
  revised.yaw = 0;  // half a turn away
  EXPECT_FALSE(revision_agrees(first, revised, first.covariance));
}

TEST(PoseRevision, WeighsTheDifferenceByTheCovariancesCrossTerms) {
  // Position sigma 1 mm with x and y correlated 0.9: a move along x = y is likely, across it not.
  PoseEstimate first = level_pose(0, 0, 0, 0.001, 0.001);
  first.covariance(0, 1) = first.covariance(1, 0) = 0.9e-6;
  const PoseCovariance revised_from = PoseCovariance::Zero();
  PoseEstimate along = first, across = first;
  along.x = along.y = 0.003;
  across.x = 0.003;
  across.y = -0.003;
  EXPECT_TRUE(revision_agrees(first, along, revised_from));
  EXPECT_FALSE(revision_agrees(first, across, revised_from));
}

TEST(PoseRevision, RefusedWhereTheCovarianceSaysNothing) {
  PoseEstimate first = level_pose(0, 0, 0, 0.001, 0.001);
  first.covariance(5, 5) = 0;  // no yaw variance from either pose
  PoseEstimate revised = first;
  EXPECT_FALSE(revision_agrees(first, revised, PoseCovariance::Zero()));
  first.covariance(0, 0) = std::nan("");
  first.covariance(5, 5) = 1e-6;
  EXPECT_FALSE(revision_agrees(first, revised, PoseCovariance::Zero()));
}

}  // namespace
}  // namespace irloc
