#pragma once
// The outside-in goal's figures (issue 14, docs/outside_in.md): pose rate over the frames where the
// robot is whole in view and less than 20 % hidden, position and heading RMS over those, and the
// poses that must never be: on a person or a ghost, while the robot is out of view, heading flips.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "algo/pipeline/pose_estimate.hpp"
#include "host_sim/render/outside_in_dataset.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

struct OutsideInMetrics {
  int frames = 0;
  int eligible = 0;                 // robot whole in view, < 20 % hidden, from the warm-up on
  int eligible_posed = 0;
  double pose_rate = 0;             // eligible_posed / eligible
  double position_rms = 0;          // m, over the eligible posed frames
  double heading_rms_deg = 0;
  double position_max = 0;          // m
  int poses_out_of_view = 0;        // an ok pose while the robot is not whole in view
  int poses_off_robot = 0;          // an ok pose further than gross_position (on a person, a ghost)
  int heading_flips = 0;            // an ok pose whose heading is off by more than gross_yaw
};

OutsideInMetrics compute_outside_in_metrics(const std::vector<OutsideInTruth>& truth, const std::vector<PoseEstimate>& poses,
                                            const MetricsSpec& thresholds);

// The figures alone, as outside_in_metrics.json names them.
nlohmann::ordered_json outside_in_figures_json(const OutsideInMetrics& metrics);

// `more` (keys after the figures) holds, for several cameras, each camera's figures.
void write_outside_in_metrics_json(const std::filesystem::path& path, const OutsideInMetrics& metrics,
                                   const MetricsSpec& thresholds, const std::string& scenario,
                                   const nlohmann::ordered_json& more = nlohmann::ordered_json::object());

// Lines for a person.
std::string summarize(const OutsideInMetrics& metrics);

}  // namespace irloc::sim
