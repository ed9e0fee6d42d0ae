#include "hal/config/square_config_file.hpp"

#include <string>

namespace irloc::hal {

SquareConfig read_square_config(YamlMap& square) {
  SquareConfig config;
  config.threshold = static_cast<std::uint16_t>(square.integer("threshold", 0, 65535, config.threshold));
  config.max_ray_angle = square.number("max_ray_angle", {0.1, 1.5}, config.max_ray_angle);
  config.side_tolerance = square.number("side_tolerance", {0.01, 0.3}, config.side_tolerance);
  config.angle_tolerance = square.number("angle_tolerance", {0.005, 0.5}, config.angle_tolerance);
  config.min_visible_fraction = square.number("min_visible_fraction", {0.05, 1}, config.min_visible_fraction);
  config.solid_min_fill = square.number("solid_min_fill", {0.5, 1}, config.solid_min_fill);
  config.solid_max_gap_rate = square.number("solid_max_gap_rate", {0, 1}, config.solid_max_gap_rate);
  config.dashed_min_gap_rate = square.number("dashed_min_gap_rate", {0, 2}, config.dashed_min_gap_rate);
  if (config.dashed_min_gap_rate <= config.solid_max_gap_rate) {
    square.fail_key("dashed_min_gap_rate", "must be above solid_max_gap_rate");
  }
  config.max_corner_residual = square.number("max_corner_residual", {0.001, 0.2}, config.max_corner_residual);
  config.max_side_error = square.number("max_side_error", {0.001, 0.2}, config.max_side_error);
  config.clear_win_ratio = square.number("clear_win_ratio", {1.0, 100.0}, config.clear_win_ratio);
  config.min_dash_coherence = square.number("min_dash_coherence", {0.05, 0.6}, config.min_dash_coherence);
  config.max_prior_age = square.number("max_prior_age", {0.0, 60.0}, config.max_prior_age);
  config.max_prior_distance = square.number("max_prior_distance", {0.05, 10.0}, config.max_prior_distance);
  square.reject_unknown_keys();
  return config;
}

}  // namespace irloc::hal
