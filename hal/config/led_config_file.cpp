#include "hal/config/led_config_file.hpp"

#include <optional>
#include <string>

namespace irloc::hal {
namespace {

// An optional number that must lie in [low, high].
void read_number(YamlMap& map, const std::string& key, double low, double high, double& value) {
  const std::optional<double> read = map.optional_number(key);
  if (!read) return;
  if (!(*read >= low && *read <= high)) {
    map.fail_key(key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                          std::to_string(*read));
  }
  value = *read;
}

void read_integer(YamlMap& map, const std::string& key, long long low, long long high, int& value) {
  if (!map.has(key)) return;
  const long long read = map.integer(key);
  if (read < low || read > high) {
    map.fail_key(key, "must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                          std::to_string(read));
  }
  value = static_cast<int>(read);
}

}  // namespace

led::LedSourceConfig read_led_config(YamlMap& section) {
  led::LedSourceConfig config;
  read_integer(section, "pixel_bits", 1, 16, config.pixel_bits);
  read_number(section, "threshold", 0.001, 1.0, config.threshold);
  read_number(section, "off_threshold", 0.001, 1.0, config.off_threshold);
  read_integer(section, "off_search_px", 0, 100, config.off_search_px);
  read_integer(section, "max_area", 1, 100000, config.max_area);
  read_number(section, "max_elongation", 1.0, 100.0, config.max_elongation);
  read_integer(section, "centroid_margin", 1, 20, config.centroid_margin);
  read_integer(section, "search_detections", 2, 32, config.search_detections);
  read_integer(section, "max_hypotheses", 1, 100000000, config.max_hypotheses);
  read_number(section, "search_gate_px", 0.1, 100.0, config.search_gate_px);
  read_number(section, "accept_gate_px", 0.05, 100.0, config.accept_gate_px);
  read_number(section, "max_rms_px", 0.01, 100.0, config.max_rms_px);
  read_integer(section, "max_missing", 0, 100, config.max_missing);
  read_number(section, "max_missing_fraction", 0.0, 1.0, config.max_missing_fraction);
  read_number(section, "edge_margin_px", 0.0, 1000.0, config.edge_margin_px);
  read_number(section, "max_range", 0.1, 1000.0, config.max_range);
  read_number(section, "max_tilt", 0.0, 1.5, config.max_tilt);
  read_number(section, "min_height", -100.0, 100.0, config.min_height);
  read_number(section, "max_height", -100.0, 100.0, config.max_height);
  if (config.max_height < config.min_height) section.fail_key("max_height", "must not be below min_height");
  read_number(section, "distinct_position", 0.001, 10.0, config.distinct_position);
  read_number(section, "distinct_angle", 0.0001, 1.0, config.distinct_angle);
  read_number(section, "track_gate_px", 0.1, 1000.0, config.track_gate_px);
  read_number(section, "track_timeout", 0.0, 100.0, config.track_timeout);
  read_number(section, "track_max_jump", 0.001, 100.0, config.track_max_jump);
  read_number(section, "pixel_sigma", 0.001, 100.0, config.pixel_sigma);
  read_number(section, "loss_scale_px", 0.01, 100.0, config.loss_scale_px);
  section.reject_unknown_keys();
  return config;
}

}  // namespace irloc::hal
