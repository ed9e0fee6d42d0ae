#pragma once
// The survey estimator on the corridor (corridor.hpp): made for its camera and mount.

#include <cstddef>

#include <Eigen/Core>

#include "algo/geometry/pose.hpp"
#include "algo/map/marker_map.hpp"
#include "algo/survey/survey_estimator.hpp"
#include "tests/survey/corridor.hpp"

namespace irloc::test {

// A survey starting from `map`, with a graph of `max_markers` (the corridor's 12 to 14 fit 16).
inline survey::SurveyEstimator corridor_survey(const MarkerMap& map, std::size_t max_markers = 16) {
  survey::SurveyConfig config;
  config.max_markers = max_markers;
  return survey::SurveyEstimator(corridor_camera(), corridor_mount(), map, config);
}

// Per axis (x, y, z, yaw): each surveyed marker's error in units of its written sigma, squared and
// summed over the maps added.
struct NormalizedErrors {
  Eigen::Vector4d squares = Eigen::Vector4d::Zero();
  int markers = 0;

  void add(const MarkerMap& estimated, const MarkerMap& truth) {
    for (const DotMarker& marker : estimated.dot_markers) {
      if (marker.fixed) continue;
      const DotMarker& real = *truth.find_dot_marker(marker.id);
      const Eigen::Vector3d offset = marker.origin - real.origin;
      const Eigen::Vector4d error(offset.x(), offset.y(), offset.z(), wrap_angle(marker.yaw - real.yaw));
      squares += error.cwiseQuotient(*marker.sigma).cwiseAbs2();
      ++markers;
    }
  }
  Eigen::Vector4d rms() const { return (squares / markers).cwiseSqrt(); }
};

}  // namespace irloc::test
