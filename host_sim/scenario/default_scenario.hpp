#pragma once
// The default scenario compiled into irloc-sim (host_sim/scenarios/default_loop.yaml).

#include <string_view>

namespace irloc::sim {

// The YAML text of host_sim/scenarios/default_loop.yaml, embedded at build time.
std::string_view default_scenario_yaml();

}  // namespace irloc::sim
