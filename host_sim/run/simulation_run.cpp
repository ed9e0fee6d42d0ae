#include "host_sim/run/simulation_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/plots/debug_frames.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/run/outside_in_run.hpp"
#include "host_sim/run/pipeline_process.hpp"
#include "host_sim/scenario/trajectory.hpp"
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

// The frames the LED and square sources' goals count: at least 3 LED landmarks, or a whole
// square, in view at the true pose; and of the latter, those where people hide 30-50 % of a
// side of a square in view and no more of any.
void count_goal_frames(const Scenario& scenario, const std::vector<TruthRow>& truth, const std::vector<PoseEstimate>& poses,
                       Metrics& metrics) {
  const CameraModel camera(scenario.camera.intrinsics);
  struct InView {
    int leds = 0;
    bool square = false;
    double most_hidden = 0;  // of any side of a square in view
  };
  std::map<std::uint64_t, InView> in_view;
  for (const TruthRow& row : truth) {
    const Eigen::Isometry3d t_w_b = truth_pose(row);
    InView& frame = in_view[row.seq];
    frame.leds = visible_led_landmarks(camera, t_w_b, scenario.camera.mount, scenario.map);
    const double t = static_cast<double>(row.seq) / scenario.camera.frame_rate;  // as the frame was rendered
    std::vector<Eigen::Vector2d> people;
    for (const Occluder& person : scenario.people) people.push_back(occluder_position(person, t));
    const Eigen::Vector3d camera_centre = (t_w_b * scenario.camera.mount).translation();
    for (const SquareMarker& square : scenario.map.square_markers) {
      if (!square_wholly_in_view(camera, t_w_b, scenario.camera.mount, square)) continue;
      frame.square = true;
      frame.most_hidden = std::max(frame.most_hidden, most_hidden_side_fraction(camera_centre, square, scenario.people, people));
    }
  }
  for (const PoseEstimate& pose : poses) {
    const auto found = in_view.find(pose.seq);
    if (found == in_view.end()) continue;
    const InView& frame = found->second;
    if (frame.leds >= 3) {
      ++metrics.attempts_with_3_leds;
      metrics.poses_with_3_leds += pose.ok ? 1 : 0;
    }
    if (frame.square) {
      ++metrics.attempts_with_square_in_view;
      metrics.poses_with_square_in_view += pose.ok ? 1 : 0;
    }
    if (frame.square && frame.most_hidden >= 0.3 && frame.most_hidden <= 0.5) {
      ++metrics.attempts_with_square_side_part_hidden;
      metrics.poses_with_square_side_part_hidden += pose.ok ? 1 : 0;
    }
  }
}

// Debug frames: LED-on frames spread evenly over the run.
void write_debug_frames(const Scenario& scenario, const std::filesystem::path& dir, const std::filesystem::path& dataset,
                        const std::vector<TruthRow>& truth, const std::vector<PoseEstimate>& poses) {
  const CameraModel camera(scenario.camera.intrinsics);
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
}

}  // namespace

std::vector<std::filesystem::path> run_dataset_folders(const Scenario& scenario, const std::filesystem::path& dir) {
  if (!scenario.outside_in || scenario.outside_in->cameras.size() == 1) return {dir / "dataset"};
  std::vector<std::filesystem::path> folders;
  for (std::size_t i = 0; i < scenario.outside_in->cameras.size(); ++i) {
    folders.push_back(dir / ("camera_" + std::to_string(i)) / "dataset");
  }
  return folders;
}

RunOutputs run_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress) {
  if (scenario.outside_in) return run_outside_in_scenario(scenario, dir, progress);
  RunOutputs outputs;
  const std::filesystem::path dataset = run_dataset_folders(scenario, dir).front();
  std::filesystem::remove_all(dataset);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<TruthRow> truth = render_dataset(scenario, dataset, progress);
  outputs.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const std::filesystem::path pose_csv = dir / "pose.csv";
  const PipelineRun pipeline = run_irlocd(irlocd_beside_this_program(), dataset, pose_csv);
  outputs.irlocd_log = pipeline.summary_line();
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
  outputs.metrics.source_outcomes = pipeline.source_outcomes;
  count_goal_frames(scenario, truth, poses, outputs.metrics);
  write_metrics_json(dir / "metrics.json", outputs.metrics, scenario.metrics, scenario.name,
                     {"pipeline_seconds is the wall-clock time of the irlocd process (start-up included); "
                      "stages_ms is irlocd's own mean time per pose attempt of each stage"});

  plot_trajectory(dir / "trajectory.png", truth, poses, outputs.metrics, scenario.map);
  plot_errors(dir / "errors.png", truth, poses, outputs.metrics);

  write_debug_frames(scenario, dir, dataset, truth, poses);
  return outputs;
}

}  // namespace irloc::sim
