#include "io/config/led_config_file.hpp"

namespace irloc::io {
namespace {

using led::LedSourceConfig;

const Setting<LedSourceConfig> kLedSettings[] = {
    {"threshold", &LedSourceConfig::threshold, 0.001, 1, "of full scale", "an LED is brighter than this in the LED-on frame"},
    {"off_threshold", &LedSourceConfig::off_threshold, 0.001, 1, "of full scale",
     "... and than this nearby in the LED-off frame"},
    {"off_search_px", &LedSourceConfig::off_search_px, 0, 100, "px", "how far the spot may move between the two frames"},
    {"max_area", &LedSourceConfig::max_area, 1, 100000, "px", "larger spots are lamps or sunlit patches"},
    {"max_elongation", &LedSourceConfig::max_elongation, 1, 100, "", "sqrt(major / minor variance), tested from 5 px up"},
    {"centroid_margin", &LedSourceConfig::centroid_margin, 1, 20, "px", "around a spot in its centroid window"},
    {"search_detections", &LedSourceConfig::search_detections, 2, 32, "", "brightest detections the search uses"},
    {"max_hypotheses", &LedSourceConfig::max_hypotheses, 1, 100000000, "", "solver calls per search, then it gives up"},
    {"search_gate_px", &LedSourceConfig::search_gate_px, 0.1, 100, "px", "a mapped LED reprojects within this of a detection"},
    {"accept_gate_px", &LedSourceConfig::accept_gate_px, 0.05, 100, "px", "... and after refinement within this"},
    {"max_rms_px", &LedSourceConfig::max_rms_px, 0.01, 100, "px", "a fit with a larger reprojection RMS is refused"},
    {"max_missing", &LedSourceConfig::max_missing, 0, 100, "", "predicted LEDs not seen: at most the larger of this"},
    {"max_missing_fraction", &LedSourceConfig::max_missing_fraction, 0, 1, "", "... and this fraction of those predicted"},
    {"edge_margin_px", &LedSourceConfig::edge_margin_px, 0, 1000, "px", "predicted this far inside the image to be missed"},
    {"missing_brightness", &LedSourceConfig::missing_brightness, 0, 1000, "", "... and where its range says it shows this x the threshold"},
    {"cone_tolerance", &LedSourceConfig::cone_tolerance, 0, 1.5, "rad", "an LED's axis may be this far off the map's"},
    {"max_range", &LedSourceConfig::max_range, 0.1, 1000, "m", "farther LEDs are not expected to be seen"},
    {"max_leds_in_range", &LedSourceConfig::max_leds_in_range, 1, 100000, "",
     "most mapped LEDs in a 3 max_range square; a denser map is refused"},
    {"max_tilt", &LedSourceConfig::max_tilt, 0, 1.5, "rad", "base tilt a hypothesis may have (dof 6)"},
    {"min_height", &LedSourceConfig::min_height, -100, 100, "m", "lowest base z a hypothesis may have"},
    {"max_height", &LedSourceConfig::max_height, -100, 100, "m", "highest base z a hypothesis may have (not below min_height)"},
    {"distinct_position", &LedSourceConfig::distinct_position, 0.001, 10, "m", "hypotheses further apart are different poses"},
    {"distinct_angle", &LedSourceConfig::distinct_angle, 0.0001, 1, "rad", "... or turned further apart"},
    {"min_margin_leds", &LedSourceConfig::min_margin_leds, 1, 100, "",
     "the winner explains this many more LEDs than any other pose, else ambiguous"},
    {"track_gate_px", &LedSourceConfig::track_gate_px, 0.1, 1000, "px", "a tracked prediction matches a detection within this"},
    {"track_timeout", &LedSourceConfig::track_timeout, 0, 100, "s", "the track is lost this long after the last pose"},
    {"track_max_jump", &LedSourceConfig::track_max_jump, 0.001, 100, "m or rad",
     "a tracked pose may leave the prediction by this"},
    {"reach_window", &LedSourceConfig::reach_window, 0, 100, "s", "a searched pose this soon after the last one must be in the fastest robot's reach (robot.*)"},
    {"max_position_sigma", &LedSourceConfig::max_position_sigma, 0.0001, 100, "m", "a less certain x, y gives no pose"},
    {"max_yaw_sigma", &LedSourceConfig::max_yaw_sigma, 0.0001, 10, "rad", "a less certain yaw gives no pose"},
    {"pixel_sigma", &LedSourceConfig::pixel_sigma, 0.001, 100, "px", "standard deviation of a centre, for the covariance"},
    {"loss_scale_px", &LedSourceConfig::loss_scale_px, 0.01, 100, "px", "Huber scale of the refinement"},
};

}  // namespace

std::span<const Setting<LedSourceConfig>> led_settings() { return kLedSettings; }

LedSourceConfig read_led_config(YamlMap& section) {
  LedSourceConfig config;
  read_settings(section, led_settings(), config);
  if (config.max_height < config.min_height) section.fail_key("max_height", "must not be below min_height");
  section.reject_unknown_keys();
  return config;
}

}  // namespace irloc::io
