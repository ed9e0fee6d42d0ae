#pragma once
// `irloc-sim survey-map`: a surveyed map (irlocd --survey) against the truth (a rendered
// dataset's map.yaml): every dot marker's position and yaw error, the missing and the invented.
// A marker that MAP_OUT itself calls unknown (its sigma is the survey's weak prior: no sighting
// measured it) is listed apart and left out of the largest errors: its error is the drawing's.

#include <vector>

#include "algo/map/marker_map.hpp"

namespace irloc::sim {

struct SurveyMarkerError {
  int id = -1;
  double position_m = 0;  // 3-D distance, estimate to truth
  double yaw_rad = 0;     // |wrap(yaw_estimate - yaw_truth)|
};

struct SurveyCheck {
  std::vector<SurveyMarkerError> markers;  // every marker in both maps and measured by the survey
  std::vector<int> unknown;                // in both maps, with the weak prior's sigma
  std::vector<int> missing;                // in the truth, not in the estimate
  std::vector<int> invented;               // in the estimate, not in the truth
  double max_position_m = 0;
  double max_yaw_rad = 0;
};

SurveyCheck check_survey(const MarkerMap& estimate, const MarkerMap& truth);

}  // namespace irloc::sim
