#pragma once
// Writes the marker map YAML of docs/formats.md (what io/config/map_file.hpp reads), replacing
// the file atomically: a power cut leaves the old map or the new one, never a torn file.

#include <filesystem>
#include <string>

#include "algo/map/marker_map.hpp"

namespace irloc::io {

// The map as YAML text; numbers in their shortest exact form, so that reading gives back the
// same doubles.
std::string marker_map_yaml(const MarkerMap& map);

// Writes a temporary file in the same folder, fsyncs it, renames it over `path` and fsyncs the
// folder. Throws InputError naming the file when any step fails (the old file then stays).
void write_marker_map(const std::filesystem::path& path, const MarkerMap& map);

}  // namespace irloc::io
