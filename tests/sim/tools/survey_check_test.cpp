// The survey checker: a marker that MAP_OUT keeps at the weak prior's sigma (unknown) is listed
// apart and does not set the largest error; a marker with a measured sigma does, however far off.
#include "host_sim/tools/survey_check.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace irloc::sim {
namespace {

DotMarker marker_at(int id, double x, std::optional<Eigen::Vector4d> sigma = std::nullopt) {
  DotMarker marker;
  marker.id = id;
  marker.origin = Eigen::Vector3d(x, 0, 2.6);
  marker.sigma = sigma;
  return marker;
}

TEST(SurveyCheck, AMarkerKeptAtTheWeakPriorIsUnknownAndLeftOutOfTheLargestError) {
  MarkerMap truth, estimate;
  truth.dot_markers = {marker_at(1, 0.0), marker_at(2, 1.8), marker_at(3, 3.6)};
  estimate.dot_markers = {marker_at(1, 0.0, Eigen::Vector4d(0, 0, 0, 0)),
                          marker_at(2, 1.801, Eigen::Vector4d(0.001, 0.001, 0.001, 0.001)),
                          marker_at(3, 3.8, Eigen::Vector4d(1, 1, 1, 1))};
  const SurveyCheck check = check_survey(estimate, truth);
  EXPECT_THAT(check.unknown, testing::ElementsAre(3));
  EXPECT_EQ(check.markers.size(), 2U);
  EXPECT_NEAR(check.max_position_m, 0.001, 1e-9);
  EXPECT_TRUE(check.missing.empty());
  EXPECT_TRUE(check.invented.empty());
}

TEST(SurveyCheck, AMarkerWithAMeasuredSigmaCountsHoweverFarOff) {
  MarkerMap truth, estimate;
  truth.dot_markers = {marker_at(1, 0.0), marker_at(2, 1.8)};
  estimate.dot_markers = {marker_at(1, 0.0), marker_at(2, 2.0, Eigen::Vector4d(0.05, 0.05, 0.05, 0.05))};
  const SurveyCheck check = check_survey(estimate, truth);
  EXPECT_TRUE(check.unknown.empty());
  EXPECT_NEAR(check.max_position_m, 0.2, 1e-9);
}

}  // namespace
}  // namespace irloc::sim
