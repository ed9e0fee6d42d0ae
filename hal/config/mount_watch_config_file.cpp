#include "hal/config/mount_watch_config_file.hpp"

namespace irloc::hal {

calibration::MountWatchConfig read_mount_watch_config(YamlMap& section) {
  calibration::MountWatchConfig config;
  config.enabled = section.boolean("enabled", config.enabled);
  config.tolerance = section.number("tolerance", {0.0002, 0.2}, config.tolerance);
  config.time_constant = section.number("time_constant", {1.0, 3600.0}, config.time_constant);
  config.sigmas = section.number("sigmas", {1.0, 10.0}, config.sigmas);
  config.floor_sigma = section.number("floor_sigma", {0.0001, 0.1}, config.floor_sigma);
  section.reject_unknown_keys();
  return config;
}

}  // namespace irloc::hal
