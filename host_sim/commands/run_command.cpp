// irloc-sim run: render a scenario, replay it through irlocd, write metrics and plots.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "io/files/run_files.hpp"
#include "host_sim/commands/commands.hpp"
#include "host_sim/run/simulation_run.hpp"

namespace irloc::sim {
namespace {

// irlocd's summary line (one per wall camera; its stage times are in the metrics), the metrics and
// where the outputs are.
void print_run(const Scenario& scenario, const RunOutputs& outputs, const std::string& out) {
  std::printf("irloc-sim run: %s\n  rendered in %.1f s; %s\n%s", scenario.name.c_str(), outputs.render_seconds,
              outputs.irlocd_log.c_str(), summarize(outputs.metrics).c_str());
  for (std::size_t i = 0; i < outputs.cameras.size(); ++i) {
    std::printf("  camera %zu (component id %d):\n%s", i, outputs.cameras[i].component_id,
                summarize(outputs.cameras[i].metrics).c_str());
  }
  if (outputs.outside_in) {
    if (!outputs.cameras.empty()) std::printf("  combined (%d hand-overs):\n", outputs.hand_overs);
    std::printf("%s", summarize(*outputs.outside_in).c_str());
  }
  if (!outputs.cameras.empty()) {
    std::printf("  outputs: %s/{metrics.json, trajectory.png, errors.png, outside_in_metrics.json, handover.png, room.png, "
                "camera_<i>/}\n", out.c_str());
  } else {
    std::printf("  outputs: %s/{metrics.json, trajectory.png, errors.png, %s, pose.csv, dataset/}\n", out.c_str(),
                outputs.outside_in ? "outside_in_metrics.json" : "debug_frame_*.png");
  }
}

}  // namespace

void add_run_command(CommandLine& command_line) {
  struct Options {
    std::string scenario, out = "irloc-sim-run";
    int frames = 0;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("run", "render a scenario, replay it through irlocd, write metrics and plots");
  command.text("--scenario", options->scenario, "scenario YAML (default: the embedded default scenario)");
  command.text("--out", options->out, "output folder");
  command.integer("--frames", options->frames, "override the scenario's frame count", 1, 1000000);
  command.action([options] {
    io::RunFiles files;
    const Scenario scenario = scenario_input(files, options->scenario, options->frames);
    files.output_folder("--out", options->out, kRunOutputFiles);
    for (const std::filesystem::path& dataset : run_dataset_folders(scenario, options->out)) {
      files.replaced_folder("--out", dataset);
    }
    files.check();
    print_run(scenario, run_scenario(scenario, options->out, progress_bar("rendering")), options->out);
  });
}

}  // namespace irloc::sim
