#pragma once
// The survey estimator on the corridor (corridor.hpp): made for its camera and mount.

#include <cstddef>
#include <initializer_list>
#include <numbers>
#include <random>
#include <vector>

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

// Each seed's corridor (test::Corridor) driven three times on the line x = 0.9 m (out, back, out;
// 2 cm per pose, one sighting every 0.12 m), its dots carrying the pixel grid's error
// (pixel_grid_error(): `grid_error` px at most, on the image axes `grid_axes`) and fresh noise of
// `fresh` px: the surveyed maps' normalized errors; events: how many the surveys reported.
inline NormalizedErrors survey_one_line_three_times(std::initializer_list<unsigned> seeds, double grid_error,
                                                    double fresh, std::size_t& events,
                                                    const Eigen::Vector2d& grid_axes = Eigen::Vector2d::Ones()) {
  constexpr std::size_t kStride = 6;
  NormalizedErrors normalized;
  for (const unsigned seed : seeds) {
    const Corridor corridor(seed);
    survey::SurveyEstimator survey = corridor_survey(corridor.drawing);
    std::mt19937 random(seed);
    for (int pass = 0; pass < 3; ++pass) {
      const double yaw = (pass % 2 == 1 ? -1 : 1) * std::numbers::pi / 2;
      const std::vector<PassPose> poses = corridor_pass(9.6, pass % 2 == 1);
      for (std::size_t k = 0; k < poses.size(); k += kStride) {
        survey.observe(observe(corridor.truth.dot_markers, 0.9, poses[k].y, yaw, fresh, random, grid_error, grid_axes));
      }
    }
    events += survey.events().size();
    normalized.add(survey.estimated_map(), corridor.truth);
  }
  return normalized;
}

}  // namespace irloc::test
