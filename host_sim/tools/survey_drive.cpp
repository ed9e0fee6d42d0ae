#include "host_sim/tools/survey_drive.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "algo/geometry/camera_model.hpp"
#include "algo/geometry/pose.hpp"
#include "io/config/map_file.hpp"
#include "io/files/map_file_writer.hpp"
#include "io/files/output_file.hpp"
#include "io/input_error.hpp"
#include "host_sim/metrics/result_files.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/render/marker_view.hpp"
#include "host_sim/run/pipeline_process.hpp"
#include "host_sim/scenario/trajectory.hpp"

namespace irloc::sim {
namespace {

// The IDs of the stderr lines `irlocd: survey: marker ID <what>` (docs/formats.md, "Survey").
std::vector<int> reported(const std::string& log, const std::string& what) {
  std::vector<int> ids;
  std::istringstream lines(log);
  const std::string prefix = "irlocd: survey: marker ";
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(prefix, 0) != 0) continue;
    std::istringstream rest(line.substr(prefix.size()));
    int id = -1;
    std::string word;
    if (rest >> id >> word && word == what) ids.push_back(id);
  }
  return ids;
}

// Points the dataset's replay config at the start map instead of the true one.
void use_start_map(const std::filesystem::path& dataset, const std::filesystem::path& start_file) {
  std::ifstream in(dataset / "config.yaml");
  std::ostringstream text;
  text << in.rdbuf();
  std::string config = text.str();
  const std::string key = "map: map.yaml", start_key = "map: " + start_file.string();
  if (config.find(start_key) != std::string::npos) return;  // a reused dataset: done by the run that rendered it
  const std::size_t at = config.find(key);
  if (at == std::string::npos) throw io::InputError((dataset / "config.yaml").string() + ": map: not map.yaml");
  config.replace(at, key.size(), start_key);
  io::replace_file_atomically(dataset / "config.yaml", config);
}

void score_map(const MarkerMap& surveyed, const MarkerMap& truth, SurveyDriveScore& score) {
  score.map = check_survey(surveyed, truth);
  std::array<double, 4> sums{};
  for (const DotMarker& estimate : surveyed.dot_markers) {
    const DotMarker* real = truth.find_dot_marker(estimate.id);
    const bool unknown = std::count(score.map.unknown.begin(), score.map.unknown.end(), estimate.id) > 0;
    if (real == nullptr || !estimate.sigma || unknown) continue;
    const Eigen::Vector3d offset = estimate.origin - real->origin;
    const Eigen::Vector4d error(offset.x(), offset.y(), offset.z(), wrap_angle(estimate.yaw - real->yaw));
    for (int axis = 0; axis < 4; ++axis) {
      const double normalized = error[axis] / std::max((*estimate.sigma)[axis], 1e-9);
      sums[static_cast<std::size_t>(axis)] += normalized * normalized;
    }
    ++score.normalized_count;
  }
  for (std::size_t axis = 0; axis < 4; ++axis) {
    score.normalized_rms[axis] = score.normalized_count > 0 ? std::sqrt(sums[axis] / score.normalized_count) : 0;
  }
}

// What the camera saw whole in each LED-on frame, from the true poses.
struct TrueViews {
  std::map<std::uint64_t, std::set<int>> whole_in_view;  // marker IDs, by the frame's seq
  std::map<std::uint64_t, const TruthRow*> truth_of;     // by seq
  std::map<int, int> frames_seen;                        // LED-on frames, by marker ID
};

TrueViews true_views(const Scenario& scenario, const std::vector<TruthRow>& truth) {
  const CameraModel camera(scenario.camera.intrinsics);
  TrueViews views;
  for (const TruthRow& row : truth) {
    if (!row.led_on) continue;
    Eigen::Isometry3d t_w_b = Eigen::Isometry3d::Identity();
    t_w_b.linear() = rotation_from_rpy(row.roll, row.pitch, row.yaw);
    t_w_b.translation() = Eigen::Vector3d(row.x, row.y, row.z);
    const std::set<int> seen = visible_dot_markers(camera, t_w_b, scenario.camera.mount, scenario.map);
    for (const int id : seen) ++views.frames_seen[id];
    views.whole_in_view[row.seq] = seen;
    views.truth_of[row.seq] = &row;
  }
  return views;
}

// The markers seen whole in enough frames, and those of them missing from the map or left unknown.
void score_required_markers(const TrueViews& views, SurveyDriveScore& score) {
  const auto listed = [](const std::vector<int>& ids, int id) { return std::find(ids.begin(), ids.end(), id) != ids.end(); };
  for (const auto& [id, frames] : views.frames_seen) {
    if (frames < kRequiredFrames) continue;
    score.required.push_back(id);
    if (listed(score.map.missing, id) || listed(score.map.unknown, id)) score.required_missing.push_back(id);
  }
}

// The poses of the frames that saw a marker whole, against the truth.
void score_poses(const std::vector<PoseEstimate>& poses, const TrueViews& views, const MarkerMap& start,
                 SurveyDriveScore& score) {
  double sum_squares = 0;
  for (const PoseEstimate& pose : poses) {
    const auto seen = views.whole_in_view.find(pose.seq);
    if (seen == views.whole_in_view.end() || seen->second.empty()) continue;
    const bool new_only = std::none_of(seen->second.begin(), seen->second.end(),
                                       [&](int id) { return start.find_dot_marker(id) != nullptr; });
    ++score.eligible;
    score.new_only_eligible += new_only ? 1 : 0;
    if (!pose.ok) continue;
    ++score.posed;
    score.new_only_posed += new_only ? 1 : 0;
    const TruthRow& row = *views.truth_of.at(pose.seq);
    const double error = std::hypot(pose.x - row.x, pose.y - row.y);
    sum_squares += error * error;
    score.pose_max_m = std::max(score.pose_max_m, error);
    if (error > kGrossPosition || std::abs(wrap_angle(pose.yaw - row.yaw)) > kGrossYaw) ++score.gross;
  }
  score.pose_rmse_m = score.posed > 0 ? std::sqrt(sum_squares / score.posed) : 0;
}

}  // namespace

MarkerMap surveyed_map(const std::filesystem::path& dir) { return io::load_marker_map(dir / "surveyed.yaml"); }

SurveyDriveScore run_survey_drive(const Scenario& scenario, const MarkerMap& start, const std::filesystem::path& dir,
                                  const std::filesystem::path& irlocd, DatasetReuse reuse) {
  const std::filesystem::path dataset = dir / "dataset";
  const bool rendered = reuse == DatasetReuse::reuse_rendered && std::filesystem::exists(dataset / "truth.csv");
  std::filesystem::create_directories(dataset);
  std::vector<TruthRow> truth;
  if (rendered) {
    truth = read_truth_csv(dataset / "truth.csv");
    for (TruthRow& row : truth) row.led_on = row.seq % 2 == 0;  // truth.csv has no strobe column: the renderer's
  } else {
    truth = render_dataset(scenario, dataset);
  }
  io::write_marker_map(dir / "start.yaml", start);
  use_start_map(dataset, dir / "start.yaml");
  SurveyDriveScore score;
  score.log = run_irlocd(irlocd, dataset, dir / "pose.csv", {"--survey", (dir / "surveyed.yaml").string()}).log;
  score.moved_reported = reported(score.log, "moved");
  score.added_reported = reported(score.log, "added");
  score_map(surveyed_map(dir), scenario.map, score);

  const TrueViews views = true_views(scenario, truth);
  score_required_markers(views, score);
  score_poses(read_pose_csv(dir / "pose.csv"), views, start, score);
  return score;
}

}  // namespace irloc::sim
