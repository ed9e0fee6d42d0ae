#include "hal/config/square_config_file.hpp"

#include <optional>
#include <string>

namespace irloc::hal {
namespace {

// The value of an optional key within [low, high], or the default.
double number_in(YamlMap& map, const std::string& key, double low, double high, double fallback) {
  const std::optional<double> value = map.optional_number(key);
  if (!value) return fallback;
  if (!(*value >= low && *value <= high)) {
    map.fail_key(key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                          std::to_string(*value));
  }
  return *value;
}

}  // namespace

SquareConfig read_square_config(YamlMap& square) {
  SquareConfig config;
  if (square.has("threshold")) {
    const long long threshold = square.integer("threshold");
    if (threshold < 0 || threshold > 65535) square.fail_key("threshold", "must be 0 (automatic) to 65535");
    config.threshold = static_cast<std::uint16_t>(threshold);
  }
  config.max_ray_angle = number_in(square, "max_ray_angle", 0.1, 1.5, config.max_ray_angle);
  config.side_tolerance = number_in(square, "side_tolerance", 0.01, 0.3, config.side_tolerance);
  config.angle_tolerance = number_in(square, "angle_tolerance", 0.005, 0.5, config.angle_tolerance);
  config.min_visible_fraction = number_in(square, "min_visible_fraction", 0.05, 1, config.min_visible_fraction);
  config.solid_min_fill = number_in(square, "solid_min_fill", 0.5, 1, config.solid_min_fill);
  config.solid_max_gap_rate = number_in(square, "solid_max_gap_rate", 0, 1, config.solid_max_gap_rate);
  config.dashed_min_gap_rate = number_in(square, "dashed_min_gap_rate", 0, 2, config.dashed_min_gap_rate);
  if (config.dashed_min_gap_rate <= config.solid_max_gap_rate) {
    square.fail_key("dashed_min_gap_rate", "must be above solid_max_gap_rate");
  }
  config.max_corner_residual = number_in(square, "max_corner_residual", 0.001, 0.2, config.max_corner_residual);
  config.max_side_error = number_in(square, "max_side_error", 0.001, 0.2, config.max_side_error);
  config.clear_win_ratio = number_in(square, "clear_win_ratio", 1.0, 100.0, config.clear_win_ratio);
  square.reject_unknown_keys();
  return config;
}

}  // namespace irloc::hal
