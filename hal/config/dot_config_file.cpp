#include "hal/config/dot_config_file.hpp"

#include <optional>
#include <string>

namespace irloc::hal {
namespace {

void read_component(YamlMap& parent, const std::string& key, dot::GreyLevelComponent& component) {
  std::optional<YamlMap> read = parent.optional_map(key);
  if (!read) return;
  YamlMap& map = *read;
  component.weight = map.number("weight", {1e-6, 1.0}, component.weight);
  component.mean = map.number("mean", {0.0, 65535.0}, component.mean);
  component.sigma = map.number("sigma", {1e-3, 65535.0}, component.sigma);
  map.reject_unknown_keys();
}

}  // namespace

dot::DotSourceConfig read_dot_config(YamlMap& section) {
  dot::DotSourceConfig config;
  config.pixel_bits = static_cast<decltype(config.pixel_bits)>(section.integer("pixel_bits", 1, 16, config.pixel_bits));
  config.threshold = static_cast<decltype(config.threshold)>(section.integer("threshold", 0, 65535, config.threshold));
  config.threshold_sigmas = section.number("threshold_sigmas", {1.0, 100.0}, config.threshold_sigmas);
  config.min_threshold = static_cast<decltype(config.min_threshold)>(section.integer("min_threshold", 1, 65535, config.min_threshold));
  config.threshold_rows = static_cast<decltype(config.threshold_rows)>(section.integer("threshold_rows", 1, 100000, config.threshold_rows));
  config.ceiling_distance = section.number("ceiling_distance", {0.0, 100.0}, config.ceiling_distance);
  config.min_area = static_cast<decltype(config.min_area)>(section.integer("min_area", 1, 1 << 20, config.min_area));
  config.max_area_factor = section.number("max_area_factor", {1.0, 1000.0}, config.max_area_factor);
  config.max_elongation = section.number("max_elongation", {1.0, 100.0}, config.max_elongation);
  config.min_contrast = section.number("min_contrast", {0.0, 1.0}, config.min_contrast);
  config.link_factor = section.number("link_factor", {0.5, 3.0}, config.link_factor);
  config.scale_tolerance = section.number("scale_tolerance", {1.0, 10.0}, config.scale_tolerance);
  config.max_side_ratio_error = section.number("max_side_ratio_error", {0.0, 1.0}, config.max_side_ratio_error);
  config.max_right_angle_error = section.number("max_right_angle_error", {0.0, 1.5}, config.max_right_angle_error);
  config.snap_tolerance = section.number("snap_tolerance", {0.05, 0.5}, config.snap_tolerance);
  config.min_cell_margin = section.number("min_cell_margin", {-1.0, 1.0}, config.min_cell_margin);
  config.refine_loss_scale_px = section.number("refine_loss_scale_px", {0.01, 100.0}, config.refine_loss_scale_px);
  config.marker_gate_px = section.number("marker_gate_px", {0.01, 1000.0}, config.marker_gate_px);
  config.min_pixel_sigma = section.number("min_pixel_sigma", {0.001, 10.0}, config.min_pixel_sigma);
  if (std::optional<YamlMap> grey = section.optional_map("grey_levels")) {
    read_component(*grey, "dot", config.grey_levels.dot);
    read_component(*grey, "clutter", config.grey_levels.clutter);
    grey->reject_unknown_keys();
  }
  config.rms_scale_px = section.number("rms_scale_px", {0.01, 100.0}, config.rms_scale_px);
  config.full_margin = section.number("full_margin", {0.01, 1.0}, config.full_margin);
  config.confidence_floor = section.number("confidence_floor", {0.0, 1.0}, config.confidence_floor);
  section.reject_unknown_keys();
  return config;
}

}  // namespace irloc::hal
