#pragma once
// The optional `dot:` section of the config YAML: the dot-marker path's tunables
// (algo/markers/dot/dot_source_config.hpp, docs/dot_markers.md), and the `front_end:` section and
// `camera.pixel_bits`, which the dot config carries for the shared front end. Every key is
// optional; unknown keys are errors.

#include <span>

#include "algo/markers/dot/dot_source_config.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

// The `dot:` section, except `grey_levels`.
std::span<const Setting<dot::DotSourceConfig>> dot_settings();
// Each of `grey_levels.dot` and `grey_levels.clutter`.
std::span<const Setting<dot::GreyLevelComponent>> grey_level_settings();
// The `front_end:` section: the strobe difference's threshold shared by every source's blobs.
std::span<const Setting<dot::DotSourceConfig>> front_end_settings();
// `camera.pixel_bits`: the camera's pixel depth.
std::span<const Setting<dot::DotSourceConfig>> camera_pixel_settings();

// Reads the `dot:` section into `config`; throws InputError naming file, line and field. The
// section still takes the keys that moved to `front_end:` and `camera:` under their old names
// (`dot.threshold`, `dot.pixel_bits`, ...), unless the config gives them in their new place too.
void read_dot_config(YamlMap& section, dot::DotSourceConfig& config);

}  // namespace irloc::io
