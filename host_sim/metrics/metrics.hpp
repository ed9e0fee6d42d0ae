#pragma once
// Accuracy of a run: the pose attempts of the pipeline against the ground truth of the frames
// they were computed from (docs/simulator.md, "metrics.json").

#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// Error of one ok pose against the truth at its frame.
struct PoseError {
  std::uint64_t seq = 0;
  double t = 0;          // seconds from the first truth row
  double position = 0;   // metres, Euclidean distance of the positions
  double yaw = 0;        // radians, |wrapped yaw difference|
  bool gross = false;
  bool wrong_id = false;
};

struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0, max = 0;
};

struct Metrics {
  std::size_t frames = 0;          // rows of truth.csv
  std::size_t attempts = 0;        // pose CSV rows
  std::size_t poses_ok = 0;
  std::size_t without_truth = 0;   // ok rows whose seq has no truth row (a pipeline bug)
  double detection_rate = 0;       // poses_ok / attempts
  ErrorStats position, yaw;        // over every ok pose with truth
  ErrorStats position_inliers, yaw_inliers;  // the same without gross errors
  std::size_t gross_errors = 0;
  std::size_t wrong_ids = 0;       // ok poses naming a dot marker that was not in view
  // Pose attempts at frames with at least 3 LED landmarks in view, and those with an ok pose
  // (the LED source's goal; 0 when the map has no LEDs).
  std::size_t attempts_with_3_leds = 0;
  std::size_t poses_with_3_leds = 0;
  // Pose attempts at frames with a square marker's whole tape in view, and those with an ok pose
  // (the square path's goal; 0 when the map has no squares).
  std::size_t attempts_with_square_in_view = 0;
  std::size_t poses_with_square_in_view = 0;
  // Of those, the attempts where people hide 30-50 % of some side of a square in view (none more),
  // and those with an ok pose (the square goal with occlusion).
  std::size_t attempts_with_square_side_part_hidden = 0;
  std::size_t poses_with_square_side_part_hidden = 0;
  std::map<std::string, std::size_t> poses_by_source;
  std::vector<PoseError> errors;   // per ok pose, in pose CSV order
  // Timing: wall-clock seconds of the pipeline over the whole dataset, and per frame.
  double pipeline_seconds = 0;
  double seconds_per_frame = 0;
  // Mean time per pose attempt of each pipeline stage, ms (empty: not reported).
  std::vector<std::pair<std::string, double>> stage_ms;
  // Per pose source, its attempts by outcome ("found", or why not), as irlocd counted them.
  std::map<std::string, std::map<std::string, std::size_t>> source_outcomes;
};

// Dot marker IDs whose every dot projects into the image of each frame, by seq. A pose naming
// a marker outside this set is a wrong ID. Frames absent from the map: every ID counts as wrong.
using VisibleMarkers = std::map<std::uint64_t, std::set<int>>;

Metrics compute_metrics(const std::vector<TruthRow>& truth, const std::vector<PoseEstimate>& poses,
                        const VisibleMarkers& visible, const MetricsSpec& thresholds);

// Writes metrics.json; `notes` lists what the numbers do not cover (e.g. missing stage timings).
void write_metrics_json(const std::filesystem::path& path, const Metrics& metrics, const MetricsSpec& thresholds,
                        const std::string& scenario, const std::vector<std::string>& notes);

// A few lines for a person: detection rate, errors, gross errors, wrong IDs, timing.
std::string summarize(const Metrics& metrics);

}  // namespace irloc::sim
