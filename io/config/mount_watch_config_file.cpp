#include "io/config/mount_watch_config_file.hpp"

namespace irloc::io {
namespace {

using calibration::MountWatchConfig;

const Setting<MountWatchConfig> kMountWatchSettings[] = {
    {"enabled", &MountWatchConfig::enabled, 0, 1, "", "watch the mount's tilt (default: on for dof 3 and 4, off for 6)"},
    {"tolerance", &MountWatchConfig::tolerance, 0.0002, 0.2, "rad", "warn when the mean tilt exceeds this"},
    {"time_constant", &MountWatchConfig::time_constant, 1.0, 3600.0, "s", "memory of the average, frame time"},
    {"sigmas", &MountWatchConfig::sigmas, 1.0, 10.0, "sigmas", "how far beyond the tolerance the average must be"},
    {"floor_sigma", &MountWatchConfig::floor_sigma, 0.0001, 0.1, "rad", "how much a level robot rocks, per pose"},
};

}  // namespace

std::span<const Setting<MountWatchConfig>> mount_watch_settings() { return kMountWatchSettings; }

MountWatchConfig read_mount_watch_config(YamlMap& section) {
  MountWatchConfig config;
  read_settings(section, mount_watch_settings(), config);
  section.reject_unknown_keys();
  return config;
}

}  // namespace irloc::io
