#pragma once
// Offline tools of the dot-marker path, run on a recorded (or rendered) dataset with its config
// (docs/dot_markers.md):
//   irloc-sim fit-confidence   fit the grey-level model of the confidence to the dataset's dots
//   irloc-sim calibrate-mount  find the camera's x-y offset from the rotation centre from a
//                              spin-in-place dataset and write it into the config

#include <cstddef>
#include <filesystem>
#include <string>

#include "algo/markers/dot/dot_source_config.hpp"
#include "algo/markers/dot/mount_calibration.hpp"

namespace irloc::sim {

struct ConfidenceFit {
  dot::GreyLevelModel model;
  std::size_t samples = 0;  // dot candidates seen
};

// Runs the dot path over every strobe pair and fits the mixture to the mean intensities of all
// dot candidates (expectation-maximisation from the config's current model). Throws
// io::InputError for bad input or when there are fewer than 20 candidates.
ConfidenceFit fit_confidence(const std::filesystem::path& config, const std::filesystem::path& dataset);

// The `dot: grey_levels:` YAML of a model, to paste into the config.
std::string grey_levels_yaml(const dot::GreyLevelModel& model);

struct MountCalibration {
  dot::MountOffsetFit fit;
  double z = 0;             // the mount height, kept from the config
  std::size_t poses = 0;    // ok dot poses used
};

// Runs the dot path with the mount's x-y offset set to zero over a spin-in-place dataset and fits
// the offset. Throws io::InputError when the dataset gives no usable fit.
MountCalibration calibrate_mount(const std::filesystem::path& config, const std::filesystem::path& dataset);

// Writes `config` to `out` with camera.mount.xyz replaced by (offset x, offset y, z). The YAML is
// re-emitted: values are kept, comments and layout are not.
void write_mount(const std::filesystem::path& config, const std::filesystem::path& out, const MountCalibration& mount);

}  // namespace irloc::sim
