#pragma once
// Reads the marker map YAML file (docs/formats.md).

#include <filesystem>

#include "algo/map/marker_map.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

// Throws InputError naming the file, line and field of the first problem.
MarkerMap load_marker_map(const std::filesystem::path& path);
// The same from a mapping inside another YAML file (the simulator's scenarios).
MarkerMap read_marker_map(YamlMap& root);

}  // namespace irloc::io
