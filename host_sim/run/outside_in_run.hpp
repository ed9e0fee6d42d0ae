#pragma once
// irloc-sim run of a scenario of kind: outside_in (run_scenario's other half).

#include <filesystem>

#include "host_sim/run/simulation_run.hpp"

namespace irloc::sim {

// As run_scenario, for kind: outside_in (outside_in_run.cpp's header says what it writes).
RunOutputs run_outside_in_scenario(const Scenario& scenario, const std::filesystem::path& dir, const Progress& progress);

}  // namespace irloc::sim
