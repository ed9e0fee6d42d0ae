#include "host_sim/run/simulation_run.hpp"

#include <chrono>
#include <cstdio>
#include <map>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/plots/debug_frames.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/render/outside_in_dataset.hpp"
#include "host_sim/run/pipeline_process.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/metrics/result_files.hpp"

namespace irloc::sim {
namespace {

constexpr int kDebugFrames = 4;

Eigen::Isometry3d truth_pose(const TruthRow& row) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = rotation_from_rpy(row.roll, row.pitch, row.yaw);
  t.translation() = Eigen::Vector3d(row.x, row.y, row.z);
  return t;
}

// kind: outside_in: the wall camera's dataset through irlocd in `mode: outside_in`; no debug frames.
RunOutputs run_outside_in_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress) {
  RunOutputs outputs;
  const std::filesystem::path dataset = dir / "dataset";
  std::filesystem::remove_all(dataset);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<OutsideInTruth> truth = render_outside_in_dataset(scenario, dataset, progress);
  outputs.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::filesystem::path pose_csv = dir / "pose.csv";
  const PipelineRun pipeline = run_irlocd(irlocd_beside_this_program(), dataset, pose_csv);
  outputs.irlocd_log = pipeline.log;
  const std::vector<PoseEstimate> poses = read_pose_csv(pose_csv);

  std::vector<TruthRow> rows;
  for (const OutsideInTruth& frame : truth) rows.push_back(frame.pose);
  outputs.metrics = compute_metrics(rows, poses, {}, scenario.metrics);
  outputs.metrics.pipeline_seconds = pipeline.seconds;
  outputs.metrics.seconds_per_frame = rows.empty() ? 0 : pipeline.seconds / static_cast<double>(rows.size());
  outputs.metrics.stage_ms = pipeline.stage_ms;
  write_metrics_json(dir / "metrics.json", outputs.metrics, scenario.metrics, scenario.name,
                     {"outside-in: every frame, the robot in view or not; the goal's figures are in outside_in_metrics.json"});
  outputs.outside_in = compute_outside_in_metrics(truth, poses, scenario.metrics);
  write_outside_in_metrics_json(dir / "outside_in_metrics.json", *outputs.outside_in, scenario.metrics, scenario.name);
  plot_trajectory(dir / "trajectory.png", rows, poses, outputs.metrics, MarkerMap{});
  plot_errors(dir / "errors.png", rows, poses, outputs.metrics);
  return outputs;
}

}  // namespace

RunOutputs run_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress) {
  if (scenario.outside_in) return run_outside_in_scenario(scenario, dir, progress);
  RunOutputs outputs;
  const std::filesystem::path dataset = dir / "dataset";
  std::filesystem::remove_all(dataset);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<TruthRow> truth = render_dataset(scenario, dataset, progress);
  outputs.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::filesystem::path pose_csv = dir / "pose.csv";
  const PipelineRun pipeline = run_irlocd(irlocd_beside_this_program(), dataset, pose_csv);
  outputs.irlocd_log = pipeline.log;
  const std::vector<PoseEstimate> poses = read_pose_csv(pose_csv);

  const CameraModel camera(scenario.camera.intrinsics);
  VisibleMarkers visible;
  for (const TruthRow& row : truth) {
    visible[row.seq] = visible_dot_markers(camera, truth_pose(row), scenario.camera.mount, scenario.map);
  }
  outputs.metrics = compute_metrics(truth, poses, visible, scenario.metrics);
  outputs.metrics.pipeline_seconds = pipeline.seconds;
  outputs.metrics.seconds_per_frame = truth.empty() ? 0 : pipeline.seconds / static_cast<double>(truth.size());
  outputs.metrics.stage_ms = pipeline.stage_ms;
  std::map<std::uint64_t, int> leds_in_view;
  for (const TruthRow& row : truth) {
    leds_in_view[row.seq] = visible_led_landmarks(camera, truth_pose(row), scenario.camera.mount, scenario.map);
  }
  for (const PoseEstimate& pose : poses) {
    const auto found = leds_in_view.find(pose.seq);
    if (found == leds_in_view.end() || found->second < 3) continue;
    ++outputs.metrics.attempts_with_3_leds;
    outputs.metrics.poses_with_3_leds += pose.ok ? 1 : 0;
  }
  write_metrics_json(dir / "metrics.json", outputs.metrics, scenario.metrics, scenario.name,
                     {"pipeline_seconds is the wall-clock time of the irlocd process (start-up included); "
                      "stages_ms is irlocd's own mean time per pose attempt of each stage"});

  plot_trajectory(dir / "trajectory.png", truth, poses, outputs.metrics, scenario.map);
  plot_errors(dir / "errors.png", truth, poses, outputs.metrics);

  // Debug frames: LED-on frames spread evenly over the run.
  std::map<std::uint64_t, const TruthRow*> truth_by_seq;
  for (const TruthRow& row : truth) truth_by_seq[row.seq] = &row;
  std::vector<const PoseEstimate*> attempts;
  for (const PoseEstimate& pose : poses) {
    if (truth_by_seq.count(pose.seq) != 0) attempts.push_back(&pose);
  }
  const std::size_t count = std::min<std::size_t>(kDebugFrames, attempts.size());
  for (std::size_t i = 0; i < count; ++i) {
    const PoseEstimate& pose = *attempts[(2 * i + 1) * attempts.size() / (2 * count)];
    char name[48], frame[32];
    std::snprintf(name, sizeof name, "debug_frame_%06llu.png", static_cast<unsigned long long>(pose.seq));
    std::snprintf(frame, sizeof frame, "frame_%06llu.pgm", static_cast<unsigned long long>(pose.seq));
    write_debug_frame(dir / name, dataset / frame, camera, scenario.camera.mount, scenario.map,
                      *truth_by_seq[pose.seq], pose);
  }
  return outputs;
}

}  // namespace irloc::sim
