#include "hal/config/led_config_file.hpp"

namespace irloc::hal {

led::LedSourceConfig read_led_config(YamlMap& section) {
  led::LedSourceConfig c;
  auto integer = [&](const char* key, long long low, long long high, int& value) {
    value = static_cast<int>(section.integer(key, low, high, value));
  };
  auto number = [&](const char* key, Range range, double& value) { value = section.number(key, range, value); };
  number("threshold", {0.001, 1}, c.threshold);
  number("off_threshold", {0.001, 1}, c.off_threshold);
  integer("off_search_px", 0, 100, c.off_search_px);
  integer("max_area", 1, 100000, c.max_area);
  number("max_elongation", {1, 100}, c.max_elongation);
  integer("centroid_margin", 1, 20, c.centroid_margin);
  integer("search_detections", 2, 32, c.search_detections);
  integer("max_hypotheses", 1, 100000000, c.max_hypotheses);
  number("search_gate_px", {0.1, 100}, c.search_gate_px);
  number("accept_gate_px", {0.05, 100}, c.accept_gate_px);
  number("max_rms_px", {0.01, 100}, c.max_rms_px);
  integer("max_missing", 0, 100, c.max_missing);
  number("max_missing_fraction", {0, 1}, c.max_missing_fraction);
  number("edge_margin_px", {0, 1000}, c.edge_margin_px);
  number("cone_tolerance", {0, 1.5}, c.cone_tolerance);
  number("max_range", {0.1, 1000}, c.max_range);
  integer("max_leds_in_range", 1, 100000, c.max_leds_in_range);
  number("max_tilt", {0, 1.5}, c.max_tilt);
  number("min_height", {-100, 100}, c.min_height);
  number("max_height", {-100, 100}, c.max_height);
  if (c.max_height < c.min_height) section.fail_key("max_height", "must not be below min_height");
  number("distinct_position", {0.001, 10}, c.distinct_position);
  number("distinct_angle", {0.0001, 1}, c.distinct_angle);
  integer("min_margin_leds", 1, 100, c.min_margin_leds);
  number("track_gate_px", {0.1, 1000}, c.track_gate_px);
  number("track_timeout", {0, 100}, c.track_timeout);
  number("track_max_jump", {0.001, 100}, c.track_max_jump);
  number("reach_window", {0, 100}, c.reach_window);
  number("max_speed", {0.01, 100}, c.max_speed);
  number("max_yaw_rate", {0.01, 100}, c.max_yaw_rate);
  number("max_position_sigma", {0.0001, 100}, c.max_position_sigma);
  number("max_yaw_sigma", {0.0001, 10}, c.max_yaw_sigma);
  number("pixel_sigma", {0.001, 100}, c.pixel_sigma);
  number("loss_scale_px", {0.01, 100}, c.loss_scale_px);
  section.reject_unknown_keys();
  return c;
}

}  // namespace irloc::hal
