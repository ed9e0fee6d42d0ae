#include "host_sim/tools/survey_check.hpp"

#include <algorithm>
#include <cmath>

#include "algo/geometry/pose.hpp"
#include "algo/survey/survey_config.hpp"

namespace irloc::sim {
namespace {

// MAP_OUT's sigma of a marker no sighting measured: the weak prior (written to a few digits).
bool unknown_to_survey(const DotMarker& marker) {
  return marker.sigma && (*marker.sigma)[0] >= 0.99 * survey::SurveyConfig{}.prior_sigma_m;
}

}  // namespace

SurveyCheck check_survey(const MarkerMap& estimate, const MarkerMap& truth) {
  SurveyCheck check;
  for (const DotMarker& real : truth.dot_markers) {
    const DotMarker* found = estimate.find_dot_marker(real.id);
    if (found == nullptr) {
      check.missing.push_back(real.id);
      continue;
    }
    if (unknown_to_survey(*found)) {
      check.unknown.push_back(real.id);
      continue;
    }
    const SurveyMarkerError error{real.id, (found->origin - real.origin).norm(), std::abs(wrap_angle(found->yaw - real.yaw))};
    check.max_position_m = std::max(check.max_position_m, error.position_m);
    check.max_yaw_rad = std::max(check.max_yaw_rad, error.yaw_rad);
    check.markers.push_back(error);
  }
  for (const DotMarker& marker : estimate.dot_markers) {
    if (truth.find_dot_marker(marker.id) == nullptr) check.invented.push_back(marker.id);
  }
  return check;
}

}  // namespace irloc::sim
