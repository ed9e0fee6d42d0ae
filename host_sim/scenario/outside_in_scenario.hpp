#pragma once
// The scenario of `kind: outside_in` (docs/formats.md, docs/outside_in.md): wall cameras with
// their floor references, the robot's box, the lighting steps and the sun patch.

#include <filesystem>

#include "host_sim/scenario/scenario.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::sim {

// Everything of `root` after `seed`, `frames` and `kind`, into `scenario`.
void read_outside_in_scenario(io::YamlMap& root, const std::filesystem::path& base_dir, Scenario& scenario);

}  // namespace irloc::sim
