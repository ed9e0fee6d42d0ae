#pragma once
// The survey estimator on the corridor (corridor.hpp): made for its camera and mount.

#include <cstddef>

#include "algo/survey/survey_estimator.hpp"
#include "tests/survey/corridor.hpp"

namespace irloc::test {

// A survey starting from `map`, with a graph of `max_markers` (the corridor's 12 to 14 fit 16).
inline survey::SurveyEstimator corridor_survey(const MarkerMap& map, std::size_t max_markers = 16) {
  survey::SurveyConfig config;
  config.max_markers = max_markers;
  return survey::SurveyEstimator(corridor_camera(), corridor_mount(), map, config);
}

}  // namespace irloc::test
