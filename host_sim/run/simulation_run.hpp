#pragma once
// `irloc-sim run`: render a scenario, replay it through irlocd, measure and draw the result.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "host_sim/render/dataset_render.hpp"
#include "host_sim/metrics/metrics.hpp"
#include "host_sim/metrics/outside_in_metrics.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// One wall camera's own run in an outside-in scenario with several cameras.
struct WallCameraRun {
  int component_id = 0;
  OutsideInMetrics metrics;
  std::string irlocd_log;  // all that this camera's irlocd wrote to stderr
};

struct RunOutputs {
  Metrics metrics;                             // several wall cameras: of the combined stream
  std::optional<OutsideInMetrics> outside_in;  // kind: outside_in (several cameras: combined)
  std::vector<WallCameraRun> cameras;          // several wall cameras: each camera's own
  int hand_overs = 0;                          // several wall cameras: changes of the posing camera
  std::string irlocd_log;                      // irlocd's summary line (several cameras: one line each, named)
  double render_seconds = 0;
};

// The files run_scenario replaces in DIR (irloc-sim checks them against its inputs first);
// DIR/dataset/, DIR/camera_<i>/ and the debug frames are rewritten whole.
inline const std::vector<std::string> kRunOutputFiles = {
    "metrics.json", "pose.csv", "trajectory.png", "errors.png", "irlocd.log", "irlocd_stats.json",
    "outside_in_metrics.json", "handover.png", "room.png"};

// The dataset folders run_scenario removes and renders anew: DIR/dataset, or with several wall
// cameras DIR/camera_<i>/dataset (irloc-sim checks them first: io::RunFiles::replaced_folder).
std::vector<std::filesystem::path> run_dataset_folders(const Scenario& scenario, const std::filesystem::path& dir);

// Writes DIR/dataset/ (the rendered dataset), DIR/pose.csv, DIR/metrics.json,
// DIR/trajectory.png, DIR/errors.png and DIR/debug_frame_<seq>.png (a few LED-on frames).
// An outside-in scenario writes DIR/outside_in_metrics.json instead of the debug frames; with
// several cameras, each camera's dataset, pose CSV, irlocd log, metrics and plots go to
// DIR/camera_<i>/, and DIR holds the combined stream's (docs/outside_in.md), handover.png and room.png.
// Throws io::InputError for any failure, irlocd's included.
RunOutputs run_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress = {});

}  // namespace irloc::sim
