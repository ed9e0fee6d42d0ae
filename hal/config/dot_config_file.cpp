#include "hal/config/dot_config_file.hpp"

#include <string>

namespace irloc::hal {
namespace {

// An optional number that must lie in [low, high].
void read_number(YamlMap& map, const std::string& key, double low, double high, double& value) {
  const std::optional<double> read = map.optional_number(key);
  if (!read) return;
  if (*read < low || *read > high) {
    map.fail_key(key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                          std::to_string(*read));
  }
  value = *read;
}

template <typename Integer>
void read_integer(YamlMap& map, const std::string& key, long long low, long long high, Integer& value) {
  if (!map.has(key)) {
    map.ignore(key);
    return;
  }
  const long long read = map.integer(key);
  if (read < low || read > high) {
    map.fail_key(key, "must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                          std::to_string(read));
  }
  value = static_cast<Integer>(read);
}

void read_component(YamlMap& parent, const std::string& key, dot::GreyLevelComponent& component) {
  if (!parent.has(key)) {
    parent.ignore(key);
    return;
  }
  YamlMap map = parent.map(key);
  read_number(map, "weight", 1e-6, 1.0, component.weight);
  read_number(map, "mean", 0.0, 65535.0, component.mean);
  read_number(map, "sigma", 1e-3, 65535.0, component.sigma);
  map.reject_unknown_keys();
}

}  // namespace

dot::DotSourceConfig read_dot_config(YamlMap& section) {
  dot::DotSourceConfig config;
  read_integer(section, "pixel_bits", 1, 16, config.pixel_bits);
  read_integer(section, "threshold", 0, 65535, config.threshold);
  read_number(section, "threshold_sigmas", 1.0, 100.0, config.threshold_sigmas);
  read_integer(section, "min_threshold", 1, 65535, config.min_threshold);
  read_integer(section, "threshold_rows", 1, 100000, config.threshold_rows);
  read_number(section, "ceiling_distance", 0.0, 100.0, config.ceiling_distance);
  read_integer(section, "min_area", 1, 1 << 20, config.min_area);
  read_number(section, "max_area_factor", 1.0, 1000.0, config.max_area_factor);
  read_number(section, "max_elongation", 1.0, 100.0, config.max_elongation);
  read_number(section, "min_contrast", 0.0, 1.0, config.min_contrast);
  read_number(section, "link_factor", 0.5, 3.0, config.link_factor);
  read_number(section, "scale_tolerance", 1.0, 10.0, config.scale_tolerance);
  read_number(section, "max_side_ratio_error", 0.0, 1.0, config.max_side_ratio_error);
  read_number(section, "max_right_angle_error", 0.0, 1.5, config.max_right_angle_error);
  read_number(section, "snap_tolerance", 0.05, 0.5, config.snap_tolerance);
  read_number(section, "min_cell_margin", -1.0, 1.0, config.min_cell_margin);
  read_number(section, "refine_loss_scale_px", 0.01, 100.0, config.refine_loss_scale_px);
  read_number(section, "marker_gate_px", 0.01, 1000.0, config.marker_gate_px);
  read_number(section, "min_pixel_sigma", 0.001, 10.0, config.min_pixel_sigma);
  if (section.has("grey_levels")) {
    YamlMap grey = section.map("grey_levels");
    read_component(grey, "dot", config.grey_levels.dot);
    read_component(grey, "clutter", config.grey_levels.clutter);
    grey.reject_unknown_keys();
  } else {
    section.ignore("grey_levels");
  }
  read_number(section, "rms_scale_px", 0.01, 100.0, config.rms_scale_px);
  read_number(section, "full_margin", 0.01, 1.0, config.full_margin);
  read_number(section, "confidence_floor", 0.0, 1.0, config.confidence_floor);
  section.reject_unknown_keys();
  return config;
}

}  // namespace irloc::hal
