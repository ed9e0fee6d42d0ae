#pragma once
// The optional `dot:` section of the config YAML: the dot-marker path's tunables
// (algo/markers/dot/dot_source_config.hpp, docs/dot_markers.md). Every key is optional; unknown
// keys are errors.

#include "algo/markers/dot/dot_source_config.hpp"
#include "hal/config/yaml_reader.hpp"

namespace irloc::hal {

// Reads the section into the defaults; throws InputError naming file, line and field.
dot::DotSourceConfig read_dot_config(YamlMap& section);

}  // namespace irloc::hal
