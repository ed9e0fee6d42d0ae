#pragma once
// `irloc-sim run`: render a scenario, replay it through irlocd, measure and draw the result.

#include <filesystem>
#include <optional>
#include <string>

#include "host_sim/render/dataset_render.hpp"
#include "host_sim/metrics/metrics.hpp"
#include "host_sim/metrics/outside_in_metrics.hpp"
#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

struct RunOutputs {
  Metrics metrics;
  std::optional<OutsideInMetrics> outside_in;  // kind: outside_in
  std::string irlocd_log;
  double render_seconds = 0;
};

// Writes DIR/dataset/ (the rendered dataset), DIR/pose.csv, DIR/metrics.json,
// DIR/trajectory.png, DIR/errors.png and DIR/debug_frame_<seq>.png (a few LED-on frames).
// An outside-in scenario writes DIR/outside_in_metrics.json instead of the debug frames.
// Throws hal::InputError for any failure, irlocd's included.
RunOutputs run_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress = {});

}  // namespace irloc::sim
