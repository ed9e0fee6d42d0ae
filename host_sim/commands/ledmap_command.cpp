// irloc-sim ledmap: a heat map of the ceiling brightness an LED ring gives a retro-reflector.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "host_sim/commands/commands.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/tools/planning.hpp"

namespace irloc::sim {

void add_ledmap_command(CommandLine& command_line) {
  struct Options {
    std::string scenario, out;
    double half_extent = 2.5;
    int cells = 120;
    double scale_max = 0;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("ledmap", "heat map of the ceiling brightness an LED ring gives a retro-reflector");
  command.text("--scenario", options->scenario, "scenario YAML (its led_ring, camera and pose at t = 0)", Need::required);
  command.text("--out", options->out, "PNG to write", Need::required);
  command.number("--half-extent", options->half_extent, "half size of the ceiling square, metres", 0.1, 100);
  command.integer("--cells", options->cells, "cells per side", 8, 1000);
  command.number("--scale-max", options->scale_max, "top of the colour scale, % of full scale (default: the peak)", 0.01, 10000);
  command.action([options] {
    const Scenario scenario = picture_scenario(options->scenario, options->out);
    HeatMap map = led_ring_brightness(scenario, options->half_extent, options->cells);
    map.title = "Retro brightness: " + std::filesystem::path(scenario.name).stem().string();
    const double peak = map.high;
    if (options->scale_max > 0) map.high = options->scale_max;
    plot_heat_map(options->out, map);
    std::printf("irloc-sim: LED ring brightness map in %s (peak %.1f %% of full scale)\n", options->out.c_str(), peak);
  });
}

}  // namespace irloc::sim
