#include "io/config/dot_config_file.hpp"

#include <optional>
#include <string>

namespace irloc::io {
namespace {

using dot::DotSourceConfig;
using dot::GreyLevelComponent;

const Setting<DotSourceConfig> kDotSettings[] = {
    {"ceiling_distance", &DotSourceConfig::ceiling_distance, 0.0, 100.0, "m",
     "camera to ceiling plane along its normal; 0: mean dot-marker z of the map less the mount's z"},
    {"min_area", &DotSourceConfig::min_area, 1, 1 << 20, "px", "smallest blob that can be a dot"},
    {"max_area_factor", &DotSourceConfig::max_area_factor, 1.0, 1000.0, "",
     "largest blob, in expected dot areas (+ 9 px)"},
    {"max_elongation", &DotSourceConfig::max_elongation, 1.0, 100.0, "",
     "sqrt(major / minor variance) of a dot, tested from 6 px up"},
    {"min_contrast", &DotSourceConfig::min_contrast, 0.0, 1.0, "",
     "(on - off) / on at a dot: lamps are bright with the LEDs off"},
    {"link_factor", &DotSourceConfig::link_factor, 0.5, 3.0, "", "dots closer than link_factor * 3 pitch join a group"},
    {"scale_tolerance", &DotSourceConfig::scale_tolerance, 1.0, 10.0, "",
     "marker size within [1/t, t] of the expected one"},
    {"max_side_ratio_error", &DotSourceConfig::max_side_ratio_error, 0.0, 1.0, "", "| |OX| / |OY| - 1 | of the direction dots"},
    {"max_right_angle_error", &DotSourceConfig::max_right_angle_error, 0.0, 1.5, "rad", "| angle XOY - 90 deg |"},
    {"snap_tolerance", &DotSourceConfig::snap_tolerance, 0.05, 0.5, "pitches", "a dot belongs to a cell within this"},
    {"min_cell_margin", &DotSourceConfig::min_cell_margin, -1.0, 1.0, "",
     "a cell's intensity test margin below which the marker is rejected"},
    {"refine_loss_scale_px", &DotSourceConfig::refine_loss_scale_px, 0.01, 100.0, "px", "Huber scale of the refinement"},
    {"marker_gate_px", &DotSourceConfig::marker_gate_px, 0.01, 1000.0, "px",
     "a marker whose dots reproject worse (RMS) is dropped"},
    {"min_pixel_sigma", &DotSourceConfig::min_pixel_sigma, 0.001, 10.0, "px",
     "least pixel noise the covariance assumes (else the fit's own residuals)"},
    {"rms_scale_px", &DotSourceConfig::rms_scale_px, 0.01, 100.0, "px", "geometric evidence exp(-rms^2 / (2 scale^2))"},
    {"full_margin", &DotSourceConfig::full_margin, 0.01, 1.0, "", "a cell margin at or above this is full evidence"},
    {"confidence_floor", &DotSourceConfig::confidence_floor, 0.0, 1.0, "", "below it the pose is reported as none"},
};

const Setting<GreyLevelComponent> kGreyLevelSettings[] = {
    {"weight", &GreyLevelComponent::weight, 1e-6, 1.0, "", "mixing weight"},
    {"mean", &GreyLevelComponent::mean, 0.0, 65535.0, "grey levels", "mean strobe difference of a blob"},
    {"sigma", &GreyLevelComponent::sigma, 1e-3, 65535.0, "grey levels", "its standard deviation"},
};

const Setting<DotSourceConfig> kFrontEndSettings[] = {
    {"threshold", &DotSourceConfig::threshold, 0, 65535, "grey levels",
     "fixed on - off threshold of the blobs; 0: from each pair's noise"},
    {"threshold_sigmas", &DotSourceConfig::threshold_sigmas, 1.0, 100.0, "sigmas",
     "from the noise: median + threshold_sigmas * sigma of the difference"},
    {"min_threshold", &DotSourceConfig::min_threshold, 1, 65535, "grey levels", "from the noise: at least this"},
    {"threshold_rows", &DotSourceConfig::threshold_rows, 1, 100000, "rows", "rows sampled (evenly spaced) for the noise"},
};

const Setting<DotSourceConfig> kCameraPixelSettings[] = {
    {"pixel_bits", &DotSourceConfig::pixel_bits, 1, 16, "bits", "significant bits of the camera's pixels"},
};

void read_grey_level_component(YamlMap& grey_levels, const std::string& key, GreyLevelComponent& component) {
  std::optional<YamlMap> map = grey_levels.optional_map(key);
  if (!map) return;
  read_settings(*map, grey_level_settings(), component);
  map->reject_unknown_keys();
}

}  // namespace

std::span<const Setting<DotSourceConfig>> dot_settings() { return kDotSettings; }
std::span<const Setting<GreyLevelComponent>> grey_level_settings() { return kGreyLevelSettings; }
std::span<const Setting<DotSourceConfig>> front_end_settings() { return kFrontEndSettings; }
std::span<const Setting<DotSourceConfig>> camera_pixel_settings() { return kCameraPixelSettings; }

void read_dot_config(YamlMap& section, DotSourceConfig& config) {
  read_settings(section, camera_pixel_settings(), config);
  read_settings(section, front_end_settings(), config);
  read_settings(section, dot_settings(), config);
  if (std::optional<YamlMap> grey = section.optional_map("grey_levels")) {
    read_grey_level_component(*grey, "dot", config.grey_levels.dot);
    read_grey_level_component(*grey, "clutter", config.grey_levels.clutter);
    grey->reject_unknown_keys();
  }
  section.reject_unknown_keys();
}

}  // namespace irloc::io
