// irloc-sim fit-confidence: fits the dot path's grey-level model to a dataset and prints it as the
// config's `dot.grey_levels` YAML.

#include <cstdio>
#include <memory>
#include <string>

#include "host_sim/commands/commands.hpp"
#include "host_sim/tools/dot_tools.hpp"

namespace irloc::sim {

void add_fit_confidence_command(CommandLine& command_line) {
  struct Options {
    std::string config, dataset;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add("fit-confidence", "fit the dot path's grey-level model to a dataset");
  command.text("--config", options->config, "config YAML", Need::required);
  command.text("--dataset", options->dataset, "dataset folder", Need::required);
  command.action([options] {
    const ConfidenceFit fit = fit_confidence(options->config, options->dataset);
    std::printf("# irloc-sim fit-confidence: %zu dot candidates of %s\n%s", fit.samples, options->dataset.c_str(),
                grey_levels_yaml(fit.model).c_str());
  });
}

}  // namespace irloc::sim
