#pragma once
// A rendered survey drive, end to end and scored against its truth (docs/survey.md, issue 28's
// goals): the scenario rendered, `irlocd --survey` run on it from a start map (a drawing, or an
// earlier survey's map), then the written map, the poses during the survey and the stderr events
// against the scenario's true map and trajectory. The score knows nothing of the estimator.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "algo/map/marker_map.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "host_sim/tools/survey_check.hpp"

namespace irloc::sim {

struct SurveyDriveScore {
  SurveyCheck map;                  // MAP_OUT against the true map: errors, missing, invented
  std::vector<int> required;        // markers whole in view in >= kRequiredFrames LED-on frames
  std::vector<int> required_missing;  // of those, not in MAP_OUT or unknown there (SurveyCheck)
  // Per axis (x, y, z, yaw): the RMS of error / sigma over MAP_OUT's markers with a sigma.
  std::array<double, 4> normalized_rms{};
  int normalized_count = 0;
  // Pose attempts with a marker whole in view ("eligible"), those with a pose, and those off the
  // truth by more than kGrossPosition or kGrossYaw; the same for the attempts where every marker
  // whole in view is one the start map lacks.
  int eligible = 0, posed = 0, gross = 0;
  int new_only_eligible = 0, new_only_posed = 0;
  double pose_rmse_m = 0, pose_max_m = 0;
  std::vector<int> moved_reported, added_reported;  // IDs on the stderr event lines, in order
  std::string log;                                  // irlocd's stderr
};

inline constexpr int kRequiredFrames = 8;
inline constexpr double kGrossPosition = 0.02;  // m
inline constexpr double kGrossYaw = 0.5 * 3.14159265358979323846 / 180;  // rad
// The sigmas fit the errors when the normalized errors' RMS per axis is within these.
inline constexpr double kMinNormalizedRms = 0.5, kMaxNormalizedRms = 1.5;

// Whether a dataset that an earlier run rendered into dir/dataset (its truth.csv written: rendering
// finished) is surveyed again instead of rendered anew: rendering is deterministic and takes minutes,
// the survey seconds (an evaluation rerun after a change to the estimator).
enum class DatasetReuse { render, reuse_rendered };

// Renders `scenario` into dir/dataset (its map.yaml: the truth), writes `start` to dir/start.yaml,
// runs `irlocd --survey dir/surveyed.yaml` on it from that map and scores the run. Throws
// io::InputError when rendering or irlocd fails.
SurveyDriveScore run_survey_drive(const Scenario& scenario, const MarkerMap& start, const std::filesystem::path& dir,
                                  const std::filesystem::path& irlocd, DatasetReuse reuse = DatasetReuse::render);

// The map dir/surveyed.yaml that run_survey_drive left.
MarkerMap surveyed_map(const std::filesystem::path& dir);

}  // namespace irloc::sim
