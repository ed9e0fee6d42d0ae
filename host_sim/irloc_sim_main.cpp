// irloc-sim: the host simulator. Renders physically grounded IR scenes from scenario files,
// replays them through irlocd, and measures the result against ground truth
// (docs/simulator.md). Each subcommand is a file of host_sim/commands/.

#include "host_sim/commands/commands.hpp"

int main(int argc, char** argv) {
  using namespace irloc::sim;
  CommandLine command_line("irloc-sim: host simulator (docs/simulator.md)");
  add_synth_command(command_line);
  add_render_command(command_line);
  add_run_command(command_line);
  add_ledmap_command(command_line);
  add_coverage_command(command_line);
  add_ledplan_command(command_line);
  add_default_scenario_command(command_line);
  add_fit_confidence_command(command_line);
  add_calibrate_mount_command(command_line);
  add_plot_residuals_command(command_line);
  add_survey_map_command(command_line);
  return command_line.run(argc, argv);
}
