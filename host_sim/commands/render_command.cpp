// irloc-sim render: a scenario to a dataset irlocd can replay (one per wall camera).

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/files/run_files.hpp"
#include "host_sim/commands/commands.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/render/outside_in_dataset.hpp"

namespace irloc::sim {

void add_render_command(CommandLine& command_line) {
  struct Options {
    std::string scenario, out;
    int frames = 0;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("render", "render a scenario to a dataset irlocd can replay");
  command.text("--scenario", options->scenario, "scenario YAML (default: the embedded default scenario)");
  command.text("--out", options->out, "dataset folder to write", Need::required);
  command.integer("--frames", options->frames, "override the scenario's frame count", 1, 1000000);
  command.action([options] {
    io::RunFiles files;
    const Scenario scenario = scenario_input(files, options->scenario, options->frames);
    const std::filesystem::path out(options->out);
    std::size_t rendered = 0;
    if (scenario.outside_in) {
      // Several wall cameras: one dataset each, OUT/camera_<i>.
      std::vector<std::filesystem::path> dirs;
      const std::size_t cameras = scenario.outside_in->cameras.size();
      for (std::size_t i = 0; i < cameras; ++i) {
        dirs.push_back(cameras == 1 ? out : out / ("camera_" + std::to_string(i)));
        files.new_folder("--out", dirs.back());
      }
      files.check();
      rendered = render_outside_in_datasets(scenario, dirs, progress_bar("rendering")).front().size();
    } else {
      files.new_folder("--out", out);
      files.check();
      rendered = render_dataset(scenario, out, progress_bar("rendering")).size();
    }
    std::printf("irloc-sim: rendered %zu frames of %s to %s\n", rendered, scenario.name.c_str(), options->out.c_str());
  });
}

}  // namespace irloc::sim
