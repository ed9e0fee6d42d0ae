#pragma once
// Reads the marker map YAML file (docs/formats.md).

#include <filesystem>

#include "algo/markers/marker_map.hpp"

namespace irloc::hal {

// Throws InputError naming the file, line and field of the first problem.
MarkerMap load_marker_map(const std::filesystem::path& path);

}  // namespace irloc::hal
