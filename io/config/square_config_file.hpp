#pragma once
// The optional `square` section of the config YAML: settings of the square tape marker path
// (docs/square_markers.md). Every key is optional; an unknown key or a value out of range is an
// InputError naming the file, line and field.

#include <span>

#include "algo/markers/square/square_config.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

std::span<const Setting<square::SquareConfig>> square_settings();

square::SquareConfig read_square_config(YamlMap& square);

}  // namespace irloc::io
