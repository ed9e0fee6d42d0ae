#pragma once
// Turns the --camera argument into a camera backend.

#include <memory>
#include <string>

#include "hal/camera.hpp"

namespace irloc::firmware {

// "dir:DATASET" replays a dataset. Frames must be width x height (from `size_source`, the
// calibration file). Throws hal::InputError for an unknown kind or a bad dataset.
std::unique_ptr<hal::Camera> open_camera(const std::string& spec, int width, int height, const std::string& size_source);

}  // namespace irloc::firmware
