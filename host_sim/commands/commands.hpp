#pragma once
// irloc-sim's subcommands (docs/simulator.md), one file each: every function adds its subcommand,
// its options and its action to the command line.

#include "host_sim/commands/command_line.hpp"

namespace irloc::sim {

void add_synth_command(CommandLine& command_line);             // a small schematic strobed dataset
void add_render_command(CommandLine& command_line);            // a scenario to a dataset
void add_run_command(CommandLine& command_line);               // render, replay through irlocd, metrics, plots
void add_ledmap_command(CommandLine& command_line);            // the LED ring's brightness on the ceiling
void add_coverage_command(CommandLine& command_line);          // landmarks in view over the floor
void add_ledplan_command(CommandLine& command_line);           // the LED source's expected error over the floor
void add_default_scenario_command(CommandLine& command_line);  // the embedded default scenario
void add_fit_confidence_command(CommandLine& command_line);    // the dot path's grey-level model from a dataset
void add_calibrate_mount_command(CommandLine& command_line);   // the camera offset from a spin in place
void add_plot_residuals_command(CommandLine& command_line);    // irlocd --calibrate's residuals as a picture
void add_survey_map_command(CommandLine& command_line);        // a surveyed map against the truth or its start

}  // namespace irloc::sim
