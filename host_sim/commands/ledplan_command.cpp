// irloc-sim ledplan: a floor map of the LED source's expected position error at the worst heading.

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "host_sim/commands/commands.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/tools/led_placement.hpp"

namespace irloc::sim {

void add_ledplan_command(CommandLine& command_line) {
  struct Options {
    std::string scenario, out;
    double cell = 0.1;
    int headings = 36;
    double pixel_sigma = 0.17;
    double scale_mm = 0;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("ledplan", "floor map of the LED source's expected position error at the worst heading");
  command.text("--scenario", options->scenario, "scenario YAML (its LED landmarks, camera, room and robot.dof)", Need::required);
  command.text("--out", options->out, "PNG to write", Need::required);
  command.number("--cell", options->cell, "floor cell size, metres", 0.001, 100);
  command.integer("--headings", options->headings, "headings tried per cell", 1, 720);
  command.number("--pixel-sigma", options->pixel_sigma, "LED centre noise, pixels (the paper's: 0.17)", 0.001, 100);
  command.number("--scale-max", options->scale_mm, "top of the colour scale, mm (default: the largest error)", 0.001, 1e6);
  command.action([options] {
    const Scenario scenario = picture_scenario(options->scenario, options->out);
    HeatMap map = led_position_error_map(scenario, options->cell, options->headings, options->pixel_sigma);
    std::size_t posed = 0;
    for (const double value : map.values) posed += std::isfinite(value) ? 1 : 0;
    const double fraction = map.values.empty() ? 0 : static_cast<double>(posed) / static_cast<double>(map.values.size());
    char title[160];
    std::snprintf(title, sizeof title, "LED position error, 1 sigma, worst heading (grey: no pose): %.0f %%", 100 * fraction);
    map.title = title;
    const double worst = map.high;
    if (options->scale_mm > 0) map.high = options->scale_mm;
    plot_heat_map(options->out, map);
    std::printf("irloc-sim: LED placement map in %s: %.1f %% of the floor gives a pose at every heading, "
                "worst error there %.1f mm\n", options->out.c_str(), 100 * fraction, worst);
  });
}

}  // namespace irloc::sim
