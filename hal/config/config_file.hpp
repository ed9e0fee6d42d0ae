#pragma once
// Reads the irloc config YAML and the calibration and map files it names (docs/formats.md).

#include <filesystem>

#include "algo/pipeline/localizer.hpp"

namespace irloc::hal {

struct RobotConfig {
  std::filesystem::path calibration_file;  // resolved against the config file's folder
  std::filesystem::path map_file;
  LocalizerSetup setup;
};

// Throws InputError naming the file (the config, the calibration or the map), line and field
// of the first problem.
RobotConfig load_robot_config(const std::filesystem::path& path);

}  // namespace irloc::hal
