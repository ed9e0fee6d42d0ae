#include "io/config/square_config_file.hpp"

namespace irloc::io {
namespace {

const Setting<square::SquareConfig> kSquareSettings[] = {
    {"threshold", &square::SquareConfig::threshold, 0, 65535, "grey levels",
     "strobe difference above which a pixel is tape; 0: from the pair's noise"},
    {"max_ray_angle", &square::SquareConfig::max_ray_angle, 0.1, 1.5, "rad", "rays further from the vertical are not mapped"},
    {"side_tolerance", &square::SquareConfig::side_tolerance, 0.01, 0.3, "",
     "side length searched within +- this fraction of d (dof 3: at most max_side_error + a tape width)"},
    {"angle_tolerance", &square::SquareConfig::angle_tolerance, 0.005, 0.5, "rad", "parallel and perpendicular sides within this"},
    {"tilted_side_tolerance", &square::SquareConfig::tilted_side_tolerance, 0.01, 0.6, "",
     "dof 6, search among the Hough peaks: side length within +- this fraction of d"},
    {"tilted_angle_tolerance", &square::SquareConfig::tilted_angle_tolerance, 0.005, 0.8, "rad",
     "dof 6, search among the Hough peaks: parallel and perpendicular within this"},
    {"min_visible_fraction", &square::SquareConfig::min_visible_fraction, 0.05, 1, "", "each side seen along this fraction"},
    {"solid_min_fill", &square::SquareConfig::solid_min_fill, 0.5, 1, "", "the solid side covered along this fraction"},
    {"solid_max_gap_rate", &square::SquareConfig::solid_max_gap_rate, 0, 1, "gaps per period", "most gaps of the solid side"},
    {"dashed_min_gap_rate", &square::SquareConfig::dashed_min_gap_rate, 0, 2, "gaps per period",
     "fewest gaps of a dashed side (above solid_max_gap_rate)"},
    {"max_corner_residual", &square::SquareConfig::max_corner_residual, 0.001, 0.2, "m",
     "RMS distance of the measured corners from the fitted square"},
    {"max_side_error", &square::SquareConfig::max_side_error, 0.001, 0.2, "", "each refined side's error, fraction of d"},
    {"clear_win_ratio", &square::SquareConfig::clear_win_ratio, 1.0, 100.0, "",
     "the best hypothesis's confidence over the best at another pose"},
    {"min_dash_coherence", &square::SquareConfig::min_dash_coherence, 0.05, 0.6, "",
     "each dashed side's phase with its square's pattern"},
    {"max_prior_age", &square::SquareConfig::max_prior_age, 0.0, 60.0, "s",
     "an older last pose does not tell squares of one pattern apart"},
    {"max_prior_distance", &square::SquareConfig::max_prior_distance, 0.05, 10.0, "m",
     "the identified square puts the robot this near the last pose"},
};

}  // namespace

std::span<const Setting<square::SquareConfig>> square_settings() { return kSquareSettings; }

square::SquareConfig read_square_config(YamlMap& square) {
  square::SquareConfig config;
  read_settings(square, square_settings(), config);
  if (config.dashed_min_gap_rate <= config.solid_max_gap_rate) {
    square.fail_key("dashed_min_gap_rate", "must be above solid_max_gap_rate");
  }
  square.reject_unknown_keys();
  return config;
}

}  // namespace irloc::io
