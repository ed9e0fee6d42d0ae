#pragma once
// Reads the irloc config YAML and the calibration and map files it names (docs/formats.md).

#include <filesystem>

#include "algo/pipeline/localizer_setup.hpp"
#include "hal/config/yaml_reader.hpp"

namespace irloc::hal {

struct RobotConfig {
  std::filesystem::path calibration_file;  // resolved against the config file's folder
  std::filesystem::path map_file;
  LocalizerSetup setup;
};

// Throws InputError naming the file (the config, the calibration or the map), line and field
// of the first problem.
RobotConfig load_robot_config(const std::filesystem::path& path);

// T_B_C from a `camera.mount` mapping (docs/conventions.md), checked strictly.
RigidTransform read_mount(YamlMap& mount);

}  // namespace irloc::hal
