#include "host_sim/metrics/outside_in_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include <nlohmann/json.hpp>

#include "io/files/output_file.hpp"

namespace irloc::sim {

constexpr double kMostHidden = 0.2;  // the goal counts frames with the robot less than 20 % hidden

OutsideInMetrics compute_outside_in_metrics(const std::vector<OutsideInTruth>& truth, const std::vector<PoseEstimate>& poses,
                                            const MetricsSpec& thresholds) {
  OutsideInMetrics m;
  m.frames = static_cast<int>(truth.size());
  std::map<std::uint64_t, const PoseEstimate*> pose_by_seq;
  for (const PoseEstimate& pose : poses) {
    if (pose.ok) pose_by_seq[pose.seq] = &pose;
  }
  double sum_position2 = 0, sum_heading2 = 0;
  for (const OutsideInTruth& frame : truth) {
    const bool eligible = frame.whole_in_view && frame.hidden_fraction < kMostHidden &&
                          frame.pose.seq >= static_cast<std::uint64_t>(thresholds.warm_up_frames);
    m.eligible += eligible;
    const auto found = pose_by_seq.find(frame.pose.seq);
    if (found == pose_by_seq.end()) continue;
    const PoseEstimate& pose = *found->second;
    if (!frame.whole_in_view) {
      ++m.poses_out_of_view;
      continue;
    }
    const double error = std::hypot(pose.x - frame.pose.x, pose.y - frame.pose.y);
    const double heading_error = std::abs(std::remainder(pose.yaw - frame.pose.yaw, 2 * std::numbers::pi));
    m.poses_off_robot += error > thresholds.gross_position;
    m.heading_flips += heading_error > thresholds.gross_yaw;
    if (!eligible) continue;
    ++m.eligible_posed;
    sum_position2 += error * error;
    sum_heading2 += heading_error * heading_error;
    m.position_max = std::max(m.position_max, error);
  }
  if (m.eligible > 0) m.pose_rate = static_cast<double>(m.eligible_posed) / m.eligible;
  if (m.eligible_posed > 0) {
    m.position_rms = std::sqrt(sum_position2 / m.eligible_posed);
    m.heading_rms_deg = std::sqrt(sum_heading2 / m.eligible_posed) * 180 / std::numbers::pi;
  }
  return m;
}

nlohmann::ordered_json outside_in_figures_json(const OutsideInMetrics& m) {
  return {
      {"frames", m.frames},
      {"eligible_frames", m.eligible},
      {"eligible_frames_posed", m.eligible_posed},
      {"pose_rate", m.pose_rate},
      {"position_rms_m", m.position_rms},
      {"position_max_m", m.position_max},
      {"heading_rms_deg", m.heading_rms_deg},
      {"poses_out_of_view", m.poses_out_of_view},
      {"poses_off_robot", m.poses_off_robot},
      {"heading_flips", m.heading_flips}};
}

void write_outside_in_metrics_json(const std::filesystem::path& path, const OutsideInMetrics& m,
                                   const MetricsSpec& thresholds, const std::string& scenario,
                                   const nlohmann::ordered_json& more) {
  nlohmann::ordered_json json = {{"scenario", scenario}, {"warm_up_frames", thresholds.warm_up_frames}};
  json.update(outside_in_figures_json(m));
  json.update(more);
  json.update(nlohmann::ordered_json{
      {"thresholds", {{"off_robot_m", thresholds.gross_position}, {"flip_rad", thresholds.gross_yaw}, {"most_hidden", kMostHidden}}},
      {"notes", {"eligible: the robot whole in view and less than 20 % hidden, from the warm-up on; "
                 "rates and RMS over those frames; off-robot poses and flips over every ok pose in view"}}});
  io::replace_file_atomically(path, json.dump(2) + "\n", 0644, "the metrics");
}

std::string summarize(const OutsideInMetrics& m) {
  char text[512];
  std::snprintf(text, sizeof text,
                "  outside-in: pose in %d of %d eligible frames (%.1f %%), position %.1f mm RMS (max %.1f), heading %.2f deg RMS\n"
                "  poses out of view %d, off the robot %d, heading flips %d\n",
                m.eligible_posed, m.eligible, 100 * m.pose_rate, 1e3 * m.position_rms, 1e3 * m.position_max,
                m.heading_rms_deg, m.poses_out_of_view, m.poses_off_robot, m.heading_flips);
  return text;
}

}  // namespace irloc::sim
