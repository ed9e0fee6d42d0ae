#include "host_sim/run/simulation_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/metrics/camera_handover.hpp"
#include "host_sim/plots/debug_frames.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/render/outside_in_dataset.hpp"
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

// The last line of an irlocd log: its summary.
std::string last_line(const std::string& log) { return log.substr(log.find_last_of('\n') + 1); }

// kind: outside_in: each wall camera's dataset through its own irlocd in `mode: outside_in`, as a
// real installation runs them; no debug frames. One camera writes everything to DIR; several
// write each camera's own to DIR/camera_<i>/ and the combined stream's to DIR.
RunOutputs run_outside_in_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress) {
  const OutsideInSpec& spec = *scenario.outside_in;
  const bool several = spec.cameras.size() > 1;
  RunOutputs outputs;
  std::vector<std::filesystem::path> camera_dirs;
  std::vector<WallCamera> cameras;
  std::vector<std::string> names;
  const std::vector<std::filesystem::path> datasets = run_dataset_folders(scenario, dir);
  for (std::size_t i = 0; i < spec.cameras.size(); ++i) {
    camera_dirs.push_back(datasets[i].parent_path());
    std::filesystem::remove_all(datasets[i]);
    std::filesystem::create_directories(camera_dirs.back());
    cameras.push_back(wall_camera_of(spec.cameras[i]));
    names.push_back("camera " + std::to_string(i) + " (id " + std::to_string(spec.cameras[i].component_id) + ")");
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<std::vector<OutsideInTruth>> truth = render_outside_in_datasets(scenario, datasets, progress);
  outputs.render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<TruthRow> rows;
  for (const OutsideInTruth& frame : truth.front()) rows.push_back(frame.pose);
  std::vector<std::vector<PoseEstimate>> poses;
  double pipeline_seconds = 0;
  std::vector<std::pair<std::string, double>> stage_ms;
  for (std::size_t i = 0; i < spec.cameras.size(); ++i) {
    const std::filesystem::path pose_csv = camera_dirs[i] / "pose.csv";
    const std::vector<std::string> component =
        several ? std::vector<std::string>{"--component-id", std::to_string(spec.cameras[i].component_id)} : std::vector<std::string>{};
    const PipelineRun pipeline = run_irlocd(irlocd_beside_this_program(), datasets[i], pose_csv, component);
    poses.push_back(read_pose_csv(pose_csv));
    pipeline_seconds += pipeline.seconds;
    // Stage times: the mean over the cameras (every irlocd reports the same stages).
    if (stage_ms.empty()) stage_ms.assign(pipeline.stage_ms.size(), {});
    for (std::size_t s = 0; s < std::min(stage_ms.size(), pipeline.stage_ms.size()); ++s) {
      stage_ms[s].first = pipeline.stage_ms[s].first;
      stage_ms[s].second += pipeline.stage_ms[s].second / static_cast<double>(spec.cameras.size());
    }
    if (i > 0) outputs.irlocd_log += '\n';
    if (several) outputs.irlocd_log.append(names[i]).append(": ");
    outputs.irlocd_log += last_line(pipeline.log);
    if (!several) break;
    WallCameraRun run{spec.cameras[i].component_id, compute_outside_in_metrics(truth[i], poses[i], scenario.metrics), pipeline.log};
    write_outside_in_metrics_json(camera_dirs[i] / "outside_in_metrics.json", run.metrics, scenario.metrics, scenario.name,
                                  {{"camera", i}, {"component_id", run.component_id}});
    const Metrics camera_metrics = compute_metrics(rows, poses[i], {}, scenario.metrics);
    plot_trajectory(camera_dirs[i] / "trajectory.png", rows, poses[i], camera_metrics, MarkerMap{});
    plot_errors(camera_dirs[i] / "errors.png", rows, poses[i], camera_metrics);
    outputs.cameras.push_back(run);
  }

  // The stream the robot gets: one camera's poses, or the cameras' combined.
  const CameraHandOver combined = several ? combine_cameras(cameras, truth, poses) : CameraHandOver{truth.front(), poses.front(), {}, 0};
  outputs.hand_overs = combined.hand_overs;
  outputs.metrics = compute_metrics(rows, combined.poses, {}, scenario.metrics);
  outputs.metrics.pipeline_seconds = pipeline_seconds;
  const double camera_frames = static_cast<double>(rows.size() * spec.cameras.size());
  outputs.metrics.seconds_per_frame = rows.empty() ? 0 : pipeline_seconds / camera_frames;
  outputs.metrics.stage_ms = stage_ms;
  write_metrics_json(dir / "metrics.json", outputs.metrics, scenario.metrics, scenario.name,
                     {several ? "outside-in, several cameras: the combined stream (per frame the pose of the camera seeing the robot "
                                "at the finest scale); pipeline_seconds sums the irlocd runs, seconds_per_frame is per camera frame, "
                                "stages_ms the mean over the cameras; each camera's own in camera_<i>/"
                              : "outside-in: every frame, the robot in view or not; the goal's figures are in outside_in_metrics.json"});
  outputs.outside_in = compute_outside_in_metrics(combined.truth, combined.poses, scenario.metrics);
  nlohmann::ordered_json more = nlohmann::ordered_json::object();
  if (several) {
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
  plot_trajectory(dir / "trajectory.png", rows, combined.poses, outputs.metrics, MarkerMap{});
  plot_errors(dir / "errors.png", rows, combined.poses, outputs.metrics);
  if (several) {
    std::vector<std::array<Eigen::Vector2d, 4>> references;
    for (const WallCameraSpec& camera : spec.cameras) references.push_back(camera.floor_reference);
    plot_camera_handover(dir / "handover.png", truth, poses, combined, names, scenario.metrics.gross_position);
    plot_camera_room(dir / "room.png", cameras, references, combined, names);
  }
  return outputs;
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
  outputs.irlocd_log = last_line(pipeline.log);
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
  // The frames the LED and square sources' goals count: at least 3 LED landmarks, or a whole
  // square, in view at the true pose; and of the latter, those where people hide 30-50 % of a
  // side of a square in view and no more of any.
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
      ++outputs.metrics.attempts_with_3_leds;
      outputs.metrics.poses_with_3_leds += pose.ok ? 1 : 0;
    }
    if (frame.square) {
      ++outputs.metrics.attempts_with_square_in_view;
      outputs.metrics.poses_with_square_in_view += pose.ok ? 1 : 0;
    }
    if (frame.square && frame.most_hidden >= 0.3 && frame.most_hidden <= 0.5) {
      ++outputs.metrics.attempts_with_square_side_part_hidden;
      outputs.metrics.poses_with_square_side_part_hidden += pose.ok ? 1 : 0;
    }
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
