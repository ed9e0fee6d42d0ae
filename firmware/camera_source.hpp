#pragma once
// The camera factory: turns the --camera argument (or the board's camera) into a backend.

#include <atomic>
#include <memory>
#include <string>

#include "hal/camera.hpp"
#include "io/config/board_file.hpp"

namespace irloc::firmware {

struct CameraRequest {
  int width = 0;  // frames must be width x height, as calibrated in `size_source`
  int height = 0;
  std::string size_source;
  const io::BoardCamera* board_camera = nullptr;  // exposure, gain, frame duration, formats; null: defaults
  unsigned int strobe_latency_frames = 1;          // the simulated sensor's pipeline depth
  const std::atomic<bool>* stop = nullptr;         // ends a live camera's wait; may be null
};

// "dir:DATASET" replays a dataset; "libcamera" opens the board's camera (or the first one),
// "libcamera:ID" the camera with that libcamera ID; "sim" simulates a strobed sensor until
// stopped, "sim:N" for N frames (its LEDs are its built_in_strobe()); ":unpaced" delivers frames
// as fast as they are taken (soak runs), ":stall-at=SEQ" hangs before frame SEQ until stopped. Throws io::InputError for
// an unknown kind, a bad dataset or a missing camera.
std::unique_ptr<hal::Camera> open_camera(const std::string& spec, const CameraRequest& request);

// True for the specs open_camera turns into a live sensor, real or simulated (frames labelled by
// the strobe).
bool is_live_camera(const std::string& spec);

// True for the specs whose camera switches its own LEDs (its built_in_strobe()): the simulator.
bool camera_drives_its_leds(const std::string& spec);

}  // namespace irloc::firmware
