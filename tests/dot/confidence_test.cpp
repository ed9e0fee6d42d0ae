#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "algo/markers/dot/dot_confidence.hpp"
#include "algo/markers/dot/grey_level_model.hpp"

namespace irloc::dot {
namespace {

TEST(GreyLevelModel, PosteriorRisesWithIntensity) {
  const GreyLevelModel model;  // dot ~ N(80, 50), clutter ~ N(8, 4)
  EXPECT_LT(dot_posterior(model, 8), 0.05);
  EXPECT_GT(dot_posterior(model, 30), 0.99);
  double previous = 0;
  for (double intensity = 0; intensity <= 255; intensity += 1) {
    const double p = dot_posterior(model, intensity);
    EXPECT_GE(p, previous - 1e-12) << intensity;
    EXPECT_GE(p, 0.0);
    EXPECT_LE(p, 1.0);
    previous = p;
  }
}

TEST(GreyLevelModel, ExpectationMaximisationRecoversAMixture) {
  std::mt19937 random(11);
  std::normal_distribution<double> dots(150, 20), clutter(30, 10);
  std::vector<double> samples;
  for (int k = 0; k < 3000; ++k) samples.push_back(dots(random));
  for (int k = 0; k < 1000; ++k) samples.push_back(clutter(random));
  GreyLevelModel start;
  start.dot = {0.5, 100, 50};
  start.clutter = {0.5, 10, 10};
  const GreyLevelModel fitted = fit_grey_level_model(samples, start);
  EXPECT_NEAR(fitted.dot.mean, 150, 2);
  EXPECT_NEAR(fitted.dot.sigma, 20, 2);
  EXPECT_NEAR(fitted.dot.weight, 0.75, 0.03);
  EXPECT_NEAR(fitted.clutter.mean, 30, 2);
  EXPECT_NEAR(fitted.clutter.sigma, 10, 2);
}

TEST(PoseConfidence, CombinesGreyLevelsMarginsRmsAndMarkerCount) {
  const DotSourceConfig config;
  const std::vector<MarkerEvidence> one = {{0.9, 0.8}};
  const std::vector<MarkerEvidence> two = {{0.9, 0.8}, {0.9, 0.8}};
  const double single = pose_confidence(config, one, 0.2);
  EXPECT_NEAR(single, 0.9 * std::exp(-0.02), 1e-12);
  EXPECT_GT(pose_confidence(config, two, 0.2), single);
  EXPECT_LT(pose_confidence(config, one, 1.5), single);
  EXPECT_EQ(pose_confidence(config, std::vector<MarkerEvidence>{{1.0, 0.0}}, 0.0), 0.0);   // a coin-flip cell
  EXPECT_EQ(pose_confidence(config, std::vector<MarkerEvidence>{{1.0, -0.5}}, 0.0), 0.0);  // a contradicting cell
  EXPECT_NEAR(pose_confidence(config, std::vector<MarkerEvidence>{{1.0, 0.3}}, 0.0), 0.5, 1e-12);
  EXPECT_EQ(pose_confidence(config, {}, 0.0), 0.0);
}

}  // namespace
}  // namespace irloc::dot
