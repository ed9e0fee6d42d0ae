// The dot source's covariance against its real errors on independently rendered frames: the
// normalized estimation error squared (NEES) e^T C^-1 e of (x, y, yaw) must average to about 3,
// the number of estimated parameters, if the covariance tells the truth.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "algo/pipeline/localizer.hpp"
#include "tests/dot/dot_scene.hpp"

namespace irloc {
namespace {

TEST(DotCovariance, NormalizedErrorsAreConsistentWithTheCovariance) {
  test::Scene scene;
  scene.noise_sigma = 4.0;
  scene.add_marker(test::ceiling_marker(1782, 0.0, 0.0, 0.3));
  scene.add_marker(test::ceiling_marker(613, 0.5, 0.2, -1.1));
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.dof = Dof::planar3;
  setup.map.dot_markers = {test::ceiling_marker(1782, 0.0, 0.0, 0.3), test::ceiling_marker(613, 0.5, 0.2, -1.1)};
  Localizer localizer(setup);

  std::mt19937 random(11);
  std::uniform_real_distribution<double> offset(-0.25, 0.25), heading(-3.1, 3.1);
  constexpr int kTrials = 60;
  double nees_sum = 0;
  int posed = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const double x = 0.25 + offset(random), y = 0.1 + offset(random), yaw = heading(random);
    scene.world_from_base = test::level_pose(x, y, yaw);
    scene.seed = static_cast<unsigned>(100 + trial);
    Image8 on, off;
    scene.render(on, off);
    const PoseEstimate estimate = localizer.process(test::strobe_pair(on, off));
    if (!estimate.ok) continue;
    ++posed;
    const Eigen::Vector3d error(estimate.x - x, estimate.y - y, wrap_angle(estimate.yaw - yaw));
    Eigen::Matrix3d covariance;
    constexpr int kIndex[3] = {0, 1, 5};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) covariance(r, c) = estimate.covariance(kIndex[r], kIndex[c]);
    }
    nees_sum += error.dot(covariance.ldlt().solve(error));
  }
  ASSERT_GE(posed, kTrials - 2);
  const double mean_nees = nees_sum / posed;
  // Mean of ~60 chi-square(3) draws: 3 within its 99 % band is about [2.2, 4.0]; a covariance off
  // by a factor of two in variance lands at 1.5 or 6.
  EXPECT_GT(mean_nees, 2.0) << "the covariance is too pessimistic";
  EXPECT_LT(mean_nees, 4.5) << "the covariance is too optimistic";
  std::printf("mean NEES over %d frames: %.2f (ideal 3)\n", posed, mean_nees);
}

// A surveyed map is itself uncertain: with every marker drawn off its true place by its map
// sigma (5 mm, 0.3 deg), the covariance that includes the map's sigma stays consistent; without
// it the same poses look far better than they are (the two markers' baseline turns the yaw).
TEST(DotCovariance, ASurveyedMapsSigmaEntersTheCovariance) {
  test::Scene scene;
  scene.noise_sigma = 4.0;
  const std::vector<DotMarker> truth = {test::ceiling_marker(1782, 0.0, 0.0, 0.3), test::ceiling_marker(613, 0.5, 0.2, -1.1)};
  for (const DotMarker& marker : truth) scene.add_marker(marker);
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.dof = Dof::planar3;
  setup.map.dot_markers = truth;
  Localizer localizer(setup);

  const Eigen::Vector4d sigma(0.005, 0.005, 0.005, 0.005);
  std::mt19937 random(12);
  std::normal_distribution<double> unit;
  std::uniform_real_distribution<double> offset(-0.25, 0.25), heading(-3.1, 3.1);
  double nees_with = 0, nees_without = 0;
  int posed = 0;
  for (int trial = 0; trial < 60; ++trial) {
    std::vector<DotMarker> surveyed = truth;
    for (DotMarker& marker : surveyed) {
      marker.origin += sigma.head<3>().cwiseProduct(Eigen::Vector3d(unit(random), unit(random), 0));
      marker.yaw += sigma[3] * unit(random);
    }
    const double x = 0.25 + offset(random), y = 0.1 + offset(random), yaw = heading(random);
    scene.world_from_base = test::level_pose(x, y, yaw);
    scene.seed = static_cast<unsigned>(300 + trial);
    Image8 on, off;
    scene.render(on, off);
    const Eigen::Vector3d truth_pose(x, y, yaw);
    for (const bool with_sigma : {true, false}) {
      for (DotMarker& marker : surveyed) marker.sigma = with_sigma ? std::optional<Eigen::Vector4d>(sigma) : std::nullopt;
      localizer.set_dot_markers(surveyed);
      const PoseEstimate estimate = localizer.process(test::strobe_pair(on, off));
      if (!estimate.ok) continue;
      const Eigen::Vector3d error(estimate.x - x, estimate.y - y, wrap_angle(estimate.yaw - yaw));
      Eigen::Matrix3d covariance;
      constexpr int kIndex[3] = {0, 1, 5};
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) covariance(r, c) = estimate.covariance(kIndex[r], kIndex[c]);
      }
      (with_sigma ? nees_with : nees_without) += error.dot(covariance.ldlt().solve(error));
      posed += with_sigma;
    }
  }
  ASSERT_GE(posed, 50);  // a few frames refuse the two markers as inconsistent with each other
  std::printf("mean NEES with the map's sigma %.2f, without %.2f (ideal 3)\n", nees_with / posed, nees_without / posed);
  EXPECT_GT(nees_with / posed, 2.0);
  EXPECT_LT(nees_with / posed, 4.5);
  EXPECT_GT(nees_without / posed, 10.0);
}

}  // namespace
}  // namespace irloc
