#pragma once
// Writes the files irlocd reads (docs/formats.md) for a rendered dataset: the calibration as a
// ROS camera_info YAML, the marker map, and the config naming both.

#include <filesystem>

#include "host_sim/scenario/scenario.hpp"

namespace irloc::sim {

// Writes DIR/calib.yaml, DIR/map.yaml and DIR/config.yaml for the scenario's camera, mount,
// degrees of freedom and map. Throws io::InputError when a file cannot be written.
void write_replay_config(const std::filesystem::path& dir, const Scenario& scenario);

}  // namespace irloc::sim
