#pragma once
// Turns the --camera argument (or the board's camera) into a camera backend.

#include <atomic>
#include <memory>
#include <string>

#include "hal/camera.hpp"
#include "hal/config/board_file.hpp"

namespace irloc::firmware {

// "dir:DATASET" replays a dataset; "libcamera" opens the board's camera (or the first one),
// "libcamera:ID" the camera with that libcamera ID. Frames must be width x height (from
// `size_source`, the calibration file). `board_camera` (may be null: libcamera defaults) gives
// the exposure, gain, frame duration and formats. `stop` (may be null) ends a live camera's wait.
// Throws hal::InputError for an unknown kind, a bad dataset or a missing camera.
std::unique_ptr<hal::Camera> open_camera(const std::string& spec, int width, int height, const std::string& size_source,
                                         const hal::BoardCamera* board_camera = nullptr,
                                         const std::atomic<bool>* stop = nullptr);

// True for the specs open_camera turns into a live sensor (frames labelled by the strobe).
bool is_live_camera(const std::string& spec);

}  // namespace irloc::firmware
