#pragma once
// `irloc-sim run`: render a scenario, replay it through irlocd, measure and draw the result.

#include <filesystem>
#include <string>

#include "host_sim/render/dataset_render.hpp"
#include "host_sim/metrics/metrics.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

struct RunOutputs {
  Metrics metrics;
  std::string irlocd_log;
  double render_seconds = 0;
};

// Writes DIR/dataset/ (the rendered dataset), DIR/pose.csv, DIR/metrics.json,
// DIR/trajectory.png, DIR/errors.png and DIR/debug_frame_<seq>.png (a few LED-on frames).
// Throws hal::InputError for any failure, irlocd's included.
RunOutputs run_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress = {});

}  // namespace irloc::sim
