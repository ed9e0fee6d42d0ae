#include "host_sim/metrics/metrics.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <numbers>
#include <unordered_map>

#include "algo/geometry/pose.hpp"
#include "io/files/output_file.hpp"

namespace irloc::sim {
namespace {

ErrorStats stats(const std::vector<double>& values) {
  ErrorStats result;
  result.count = values.size();
  double sum2 = 0;
  for (const double value : values) {
    sum2 += value * value;
    result.max = std::max(result.max, value);
  }
  if (!values.empty()) result.rmse = std::sqrt(sum2 / static_cast<double>(values.size()));
  return result;
}

std::string json_number(double value) {
  if (!std::isfinite(value)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string json_stats(const ErrorStats& s) {
  return "{\"count\": " + std::to_string(s.count) + ", \"rmse\": " + json_number(s.rmse) +
         ", \"max\": " + json_number(s.max) + "}";
}

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "\"";
}

}  // namespace

Metrics compute_metrics(const std::vector<TruthRow>& truth, const std::vector<PoseEstimate>& poses,
                        const VisibleMarkers& visible, const MetricsSpec& thresholds) {
  Metrics metrics;
  metrics.frames = truth.size();
  metrics.attempts = poses.size();
  std::unordered_map<std::uint64_t, const TruthRow*> by_seq;
  for (const TruthRow& row : truth) by_seq[row.seq] = &row;
  const std::int64_t t0 = truth.empty() ? 0 : truth.front().t_ns;

  std::vector<double> position, yaw, position_inliers, yaw_inliers;
  for (const PoseEstimate& pose : poses) {
    if (!pose.ok) continue;
    ++metrics.poses_ok;
    ++metrics.poses_by_source[std::string(to_string(pose.source))];
    const auto found = by_seq.find(pose.seq);
    if (found == by_seq.end()) {
      ++metrics.without_truth;
      continue;
    }
    const TruthRow& t = *found->second;
    PoseError error;
    error.seq = pose.seq;
    error.t = static_cast<double>(t.t_ns - t0) * 1e-9;
    error.position = std::sqrt((pose.x - t.x) * (pose.x - t.x) + (pose.y - t.y) * (pose.y - t.y) + (pose.z - t.z) * (pose.z - t.z));
    error.yaw = std::abs(wrap_angle(pose.yaw - t.yaw));
    error.gross = error.position > thresholds.gross_position || error.yaw > thresholds.gross_yaw;
    if (pose.marker_id >= 0) {
      const auto in_view = visible.find(pose.seq);
      error.wrong_id = in_view == visible.end() || in_view->second.count(pose.marker_id) == 0;
    }
    metrics.gross_errors += error.gross ? 1 : 0;
    metrics.wrong_ids += error.wrong_id ? 1 : 0;
    position.push_back(error.position);
    yaw.push_back(error.yaw);
    if (!error.gross) {
      position_inliers.push_back(error.position);
      yaw_inliers.push_back(error.yaw);
    }
    metrics.errors.push_back(error);
  }
  metrics.detection_rate = poses.empty() ? 0 : static_cast<double>(metrics.poses_ok) / static_cast<double>(poses.size());
  metrics.position = stats(position);
  metrics.yaw = stats(yaw);
  metrics.position_inliers = stats(position_inliers);
  metrics.yaw_inliers = stats(yaw_inliers);
  return metrics;
}

void write_metrics_json(const std::filesystem::path& path, const Metrics& m, const MetricsSpec& thresholds,
                        const std::string& scenario, const std::vector<std::string>& notes) {
  std::ostringstream out;
  out << "{\n  \"scenario\": " << json_string(scenario) << ",\n"
      << "  \"frames\": " << m.frames << ",\n"
      << "  \"pose_attempts\": " << m.attempts << ",\n"
      << "  \"poses_ok\": " << m.poses_ok << ",\n"
      << "  \"detection_rate\": " << json_number(m.detection_rate) << ",\n"
      << "  \"poses_by_source\": {";
  bool first = true;
  for (const auto& [source, count] : m.poses_by_source) {
    out << (first ? "" : ", ") << json_string(source) << ": " << count;
    first = false;
  }
  out << "},\n"
      << "  \"position_error_m\": " << json_stats(m.position) << ",\n"
      << "  \"yaw_error_rad\": " << json_stats(m.yaw) << ",\n"
      << "  \"position_error_without_gross_m\": " << json_stats(m.position_inliers) << ",\n"
      << "  \"yaw_error_without_gross_rad\": " << json_stats(m.yaw_inliers) << ",\n"
      << "  \"gross_errors\": " << m.gross_errors << ",\n"
      << "  \"gross_error_thresholds\": {\"position_m\": " << json_number(thresholds.gross_position)
      << ", \"yaw_rad\": " << json_number(thresholds.gross_yaw) << "},\n"
      << "  \"wrong_ids\": " << m.wrong_ids << ",\n"
      << "  \"attempts_with_3_leds_in_view\": " << m.attempts_with_3_leds << ",\n"
      << "  \"poses_with_3_leds_in_view\": " << m.poses_with_3_leds << ",\n"
      << "  \"attempts_with_square_in_view\": " << m.attempts_with_square_in_view << ",\n"
      << "  \"poses_with_square_in_view\": " << m.poses_with_square_in_view << ",\n"
      << "  \"attempts_with_square_side_part_hidden\": " << m.attempts_with_square_side_part_hidden << ",\n"
      << "  \"poses_with_square_side_part_hidden\": " << m.poses_with_square_side_part_hidden << ",\n"
      << "  \"ok_poses_without_truth\": " << m.without_truth << ",\n"
      << "  \"timing\": {\"pipeline_seconds\": " << json_number(m.pipeline_seconds)
      << ", \"seconds_per_frame\": " << json_number(m.seconds_per_frame) << ", \"stages_ms\": ";
  if (m.stage_ms.empty()) {
    out << "null";
  } else {
    out << "{";
    for (std::size_t i = 0; i < m.stage_ms.size(); ++i) {
      out << (i ? ", " : "") << json_string(m.stage_ms[i].first) << ": " << json_number(m.stage_ms[i].second);
    }
    out << "}";
  }
  out << "},\n"
      << "  \"source_outcomes\": {";
  bool first_source = true;
  for (const auto& [source, counts] : m.source_outcomes) {
    out << (first_source ? "" : ", ") << json_string(source) << ": {";
    bool first_outcome = true;
    for (const auto& [outcome, count] : counts) {
      out << (first_outcome ? "" : ", ") << json_string(outcome) << ": " << count;
      first_outcome = false;
    }
    out << "}";
    first_source = false;
  }
  out << "},\n"
      << "  \"notes\": [";
  for (std::size_t i = 0; i < notes.size(); ++i) out << (i ? ", " : "") << json_string(notes[i]);
  out << "]\n}\n";
  io::replace_file_atomically(path, out.str(), 0644, "the metrics");
}

std::string summarize(const Metrics& m) {
  constexpr double kDegrees = 180 / std::numbers::pi;
  char line[512];
  std::string text;
  std::snprintf(line, sizeof line, "  frames %zu, pose attempts %zu, poses ok %zu: detection rate %.1f %%\n", m.frames,
                m.attempts, m.poses_ok, 100 * m.detection_rate);
  text += line;
  if (m.position.count == 0) {
    text += "  position and yaw error: n/a (no pose)\n";
  } else {
    std::snprintf(line, sizeof line,
                  "  position error: RMSE %.2f mm, max %.2f mm (%zu poses)\n"
                  "  yaw error:      RMSE %.3f deg, max %.3f deg\n",
                  1e3 * m.position.rmse, 1e3 * m.position.max, m.position.count, kDegrees * m.yaw.rmse,
                  kDegrees * m.yaw.max);
    text += line;
  }
  if (m.attempts_with_3_leds > 0) {
    std::snprintf(line, sizeof line, "  attempts with >= 3 LEDs in view %zu: pose in %.1f %%\n", m.attempts_with_3_leds,
                  100.0 * static_cast<double>(m.poses_with_3_leds) / static_cast<double>(m.attempts_with_3_leds));
    text += line;
  }
  if (m.attempts_with_square_in_view > 0) {
    std::snprintf(line, sizeof line, "  attempts with a whole square in view %zu: pose in %.1f %%\n",
                  m.attempts_with_square_in_view,
                  100.0 * static_cast<double>(m.poses_with_square_in_view) / static_cast<double>(m.attempts_with_square_in_view));
    text += line;
  }
  if (m.attempts_with_square_side_part_hidden > 0) {
    std::snprintf(line, sizeof line, "  of them with 30-50 %% of a side hidden by people %zu: pose in %.1f %%\n",
                  m.attempts_with_square_side_part_hidden,
                  100.0 * static_cast<double>(m.poses_with_square_side_part_hidden) /
                      static_cast<double>(m.attempts_with_square_side_part_hidden));
    text += line;
  }
  std::snprintf(line, sizeof line, "  gross errors %zu, wrong IDs %zu\n  pipeline time: %.2f s, %.2f ms per frame\n",
                m.gross_errors, m.wrong_ids, m.pipeline_seconds, 1e3 * m.seconds_per_frame);
  text += line;
  for (const auto& [source, counts] : m.source_outcomes) {
    text += "  " + source + " attempts:";
    for (const auto& [outcome, count] : counts) text += " " + outcome + " " + std::to_string(count) + ",";
    text.back() = '\n';
  }
  if (!m.stage_ms.empty()) {
    text += "  stages (ms per pose attempt):";
    for (const auto& [name, milliseconds] : m.stage_ms) {
      std::snprintf(line, sizeof line, " %s %.3f", name.c_str(), milliseconds);
      text += line;
    }
    text += "\n";
  }
  return text;
}

}  // namespace irloc::sim
