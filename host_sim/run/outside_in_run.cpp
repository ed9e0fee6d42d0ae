// irloc-sim run of kind: outside_in: each wall camera's dataset through its own irlocd in
// `mode: outside_in`, as a real installation runs them; no debug frames. One camera writes
// everything to DIR; several write each camera's own to DIR/camera_<i>/ and the combined
// stream's to DIR.

#include "host_sim/run/outside_in_run.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
#include <vector>

#include "host_sim/metrics/camera_handover.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/render/outside_in_dataset.hpp"
#include "host_sim/run/pipeline_process.hpp"

namespace irloc::sim {

namespace {

// The wall cameras' folders, models and names as the plots and logs name them.
struct WallCameraSetup {
  std::vector<std::filesystem::path> datasets;  // DIR/dataset, or DIR/camera_<i>/dataset
  std::vector<std::filesystem::path> dirs;      // each camera's outputs
  std::vector<WallCamera> cameras;
  std::vector<std::string> names;
};

WallCameraSetup set_up_wall_cameras(const Scenario& scenario, const std::filesystem::path& dir) {
  const OutsideInSpec& spec = *scenario.outside_in;
  WallCameraSetup setup;
  setup.datasets = run_dataset_folders(scenario, dir);
  for (std::size_t i = 0; i < spec.cameras.size(); ++i) {
    setup.dirs.push_back(setup.datasets[i].parent_path());
    std::filesystem::remove_all(setup.datasets[i]);
    std::filesystem::create_directories(setup.dirs.back());
    setup.cameras.push_back(wall_camera_of(spec.cameras[i]));
    setup.names.push_back("camera " + std::to_string(i) + " (id " + std::to_string(spec.cameras[i].component_id) + ")");
  }
  return setup;
}

// What the cameras' irlocd runs gave, over all of them.
struct WallCameraPoses {
  std::vector<std::vector<PoseEstimate>> poses;  // per camera
  double pipeline_seconds = 0;                   // summed
  std::vector<std::pair<std::string, double>> stage_ms;  // the mean over the cameras
};

// Each camera's dataset through its own irlocd; with several cameras, each camera's metrics and
// plots into its folder and its run into outputs.cameras.
WallCameraPoses run_wall_cameras(const Scenario& scenario, const WallCameraSetup& setup,
                                 const std::vector<std::vector<OutsideInTruth>>& truth, const std::vector<TruthRow>& rows,
                                 RunOutputs& outputs) {
  const OutsideInSpec& spec = *scenario.outside_in;
  const bool several = spec.cameras.size() > 1;
  WallCameraPoses result;
  for (std::size_t i = 0; i < spec.cameras.size(); ++i) {
    const std::filesystem::path pose_csv = setup.dirs[i] / "pose.csv";
    const std::vector<std::string> component =
        several ? std::vector<std::string>{"--component-id", std::to_string(spec.cameras[i].component_id)} : std::vector<std::string>{};
    const PipelineRun pipeline = run_irlocd(irlocd_beside_this_program(), setup.datasets[i], pose_csv, component);
    result.poses.push_back(read_pose_csv(pose_csv));
    result.pipeline_seconds += pipeline.seconds;
    // Every irlocd reports the same stages.
    if (result.stage_ms.empty()) result.stage_ms.assign(pipeline.stage_ms.size(), {});
    for (std::size_t s = 0; s < std::min(result.stage_ms.size(), pipeline.stage_ms.size()); ++s) {
      result.stage_ms[s].first = pipeline.stage_ms[s].first;
      result.stage_ms[s].second += pipeline.stage_ms[s].second / static_cast<double>(spec.cameras.size());
    }
    if (i > 0) outputs.irlocd_log += '\n';
    if (several) outputs.irlocd_log.append(setup.names[i]).append(": ");
    outputs.irlocd_log += pipeline.summary_line();
    if (!several) break;
    WallCameraRun run{spec.cameras[i].component_id, compute_outside_in_metrics(truth[i], result.poses[i], scenario.metrics),
                      pipeline.log};
    write_outside_in_metrics_json(setup.dirs[i] / "outside_in_metrics.json", run.metrics, scenario.metrics, scenario.name,
                                  {{"camera", i}, {"component_id", run.component_id}});
    const Metrics camera_metrics = compute_metrics(rows, result.poses[i], {}, scenario.metrics);
    plot_trajectory(setup.dirs[i] / "trajectory.png", rows, result.poses[i], camera_metrics, MarkerMap{});
    plot_errors(setup.dirs[i] / "errors.png", rows, result.poses[i], camera_metrics);
    outputs.cameras.push_back(run);
  }
  return result;
}

// outside_in_metrics.json of the combined stream, with each camera's figures when there are several.
void write_combined_outside_in_metrics(const Scenario& scenario, const std::filesystem::path& dir, const CameraHandOver& combined,
                                       RunOutputs& outputs) {
  outputs.outside_in = compute_outside_in_metrics(combined.truth, combined.poses, scenario.metrics);
  nlohmann::ordered_json more = nlohmann::ordered_json::object();
  if (!outputs.cameras.empty()) {
    more["hand_overs"] = combined.hand_overs;
    more["cameras"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < outputs.cameras.size(); ++i) {
      nlohmann::ordered_json camera = {{"camera", i}, {"component_id", outputs.cameras[i].component_id}};
      camera.update(outside_in_figures_json(outputs.cameras[i].metrics));
      more["cameras"].push_back(camera);
    }
    more["combined"] = "the figures above: eligible when any camera has the robot whole in view and less than 20 % hidden; "
                       "posed when any camera posed it; the pose of the camera seeing it at the finest scale";
  }
  write_outside_in_metrics_json(dir / "outside_in_metrics.json", *outputs.outside_in, scenario.metrics, scenario.name, more);
}

}  // namespace

RunOutputs run_outside_in_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress) {
  const OutsideInSpec& spec = *scenario.outside_in;
  const bool several = spec.cameras.size() > 1;
  RunOutputs outputs;
  const WallCameraSetup setup = set_up_wall_cameras(scenario, dir);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<OutsideInTruth>> truth = render_outside_in_datasets(scenario, setup.datasets, progress);
  outputs.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::vector<TruthRow> rows;
  for (const OutsideInTruth& frame : truth.front()) rows.push_back(frame.pose);
  const WallCameraPoses runs = run_wall_cameras(scenario, setup, truth, rows, outputs);

  // The stream the robot gets: one camera's poses, or the cameras' combined.
  const CameraHandOver combined =
      several ? combine_cameras(setup.cameras, truth, runs.poses) : CameraHandOver{truth.front(), runs.poses.front(), {}, 0};
  outputs.hand_overs = combined.hand_overs;
  outputs.metrics = compute_metrics(rows, combined.poses, {}, scenario.metrics);
  outputs.metrics.pipeline_seconds = runs.pipeline_seconds;
  const double camera_frames = static_cast<double>(rows.size() * spec.cameras.size());
  outputs.metrics.seconds_per_frame = rows.empty() ? 0 : runs.pipeline_seconds / camera_frames;
  outputs.metrics.stage_ms = runs.stage_ms;
  write_metrics_json(dir / "metrics.json", outputs.metrics, scenario.metrics, scenario.name,
                     {several ? "outside-in, several cameras: the combined stream (per frame the pose of the camera seeing the robot "
                                "at the finest scale); pipeline_seconds sums the irlocd runs, seconds_per_frame is per camera frame, "
                                "stages_ms the mean over the cameras; each camera's own in camera_<i>/"
                              : "outside-in: every frame, the robot in view or not; the goal's figures are in outside_in_metrics.json"});
  write_combined_outside_in_metrics(scenario, dir, combined, outputs);
  plot_trajectory(dir / "trajectory.png", rows, combined.poses, outputs.metrics, MarkerMap{});
  plot_errors(dir / "errors.png", rows, combined.poses, outputs.metrics);
  if (several) {
    std::vector<std::array<Eigen::Vector2d, 4>> references;
    for (const WallCameraSpec& camera : spec.cameras) references.push_back(camera.floor_reference);
    plot_camera_handover(dir / "handover.png", truth, runs.poses, combined, setup.names, scenario.metrics.gross_position);
    plot_camera_room(dir / "room.png", setup.cameras, references, combined, setup.names);
  }
  return outputs;
}

}  // namespace irloc::sim
