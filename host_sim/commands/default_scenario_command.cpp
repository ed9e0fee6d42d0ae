// irloc-sim default-scenario: prints the embedded default scenario's YAML.

#include <cstdio>

#include "host_sim/commands/commands.hpp"
#include "host_sim/scenario/default_scenario.hpp"

namespace irloc::sim {

void add_default_scenario_command(CommandLine& command_line) {
  command_line.add("default-scenario", "print the embedded default scenario YAML").action([] {
    std::fwrite(default_scenario_yaml().data(), 1, default_scenario_yaml().size(), stdout);
  });
}

}  // namespace irloc::sim
