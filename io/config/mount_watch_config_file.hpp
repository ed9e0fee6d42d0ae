#pragma once
// The optional `mount_watch:` section of the config YAML: the online watch of the mount's tilt
// (algo/calibration/mount_tilt_watch.hpp, docs/calibration.md). Every key is optional; an unknown
// key or a value out of range is an InputError naming the file, line and field.

#include <span>

#include "algo/calibration/mount_tilt_watch.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

// `enabled` defaults to on for robot.dof 3 and 4, off for 6 and in outside-in mode.
std::span<const Setting<calibration::MountWatchConfig>> mount_watch_settings();

calibration::MountWatchConfig read_mount_watch_config(YamlMap& section);

}  // namespace irloc::io
