#pragma once
// The config YAML in `mode: outside_in` (docs/formats.md, "Outside-in"; docs/outside_in.md): the
// fixed camera's calibration and floor_reference, the watched robot's dof (3) and body, an
// optional map, and the optional `outside_in:` section of the source's thresholds. Problems are
// InputErrors naming the file, line and field; a floor_reference that does not give a camera pose
// names the check that failed.

#include <span>

#include "algo/markers/outside_in/outside_in_config.hpp"
#include "io/config/config_file.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

// The `outside_in:` section (every key optional).
std::span<const Setting<outside_in::OutsideInConfig>> outside_in_settings();

// Reads everything but `mode` from root (the whole config) into config.
void read_outside_in_config(YamlMap& root, RobotConfig& config);

}  // namespace irloc::io
