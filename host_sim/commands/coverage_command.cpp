// irloc-sim coverage: a floor map of how many landmarks are in view at every heading.

#include <cstdio>
#include <memory>
#include <string>

#include "host_sim/commands/commands.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/tools/planning.hpp"

namespace irloc::sim {

void add_coverage_command(CommandLine& command_line) {
  struct Options {
    std::string scenario, out;
    int k = 3;
    double cell = 0.1;
    int headings = 36;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("coverage", "floor map of how many landmarks are in view at every heading");
  command.text("--scenario", options->scenario, "scenario YAML (its map, camera and room)", Need::required);
  command.text("--out", options->out, "PNG to write", Need::required);
  command.integer("--k", options->k, "landmarks needed in view", 1, 100);
  command.number("--cell", options->cell, "floor cell size, metres", 0.001, 100);
  command.integer("--headings", options->headings, "headings tried per cell", 1, 720);
  command.action([options] {
    const Scenario scenario = picture_scenario(options->scenario, options->out);
    HeatMap map = landmark_coverage(scenario, options->cell, options->headings);
    const double fraction = coverage_fraction(map, options->k);
    char title[128];
    std::snprintf(title, sizeof title, "Landmarks in view at every heading (>= %d on %.0f %% of the floor)", options->k,
                  100 * fraction);
    map.title = title;
    plot_heat_map(options->out, map);
    std::printf("irloc-sim: coverage map in %s: %.1f %% of the floor sees >= %d landmarks at every heading\n",
                options->out.c_str(), 100 * fraction, options->k);
  });
}

}  // namespace irloc::sim
