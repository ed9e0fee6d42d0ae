#include "firmware/camera_source.hpp"

#include <algorithm>
#include <limits>

#include "io/input_error.hpp"
#include "hal/linux/libcamera_camera.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "hal/sim/strobed_scene_camera.hpp"

namespace irloc::firmware {
namespace {

const std::string kDirPrefix = "dir:";
const std::string kLibcamera = "libcamera";
const std::string kSimulated = "sim";
constexpr std::int64_t kSimulatedFrameDurationUs = 16667;  // 60 fps without a board

bool is_libcamera(const std::string& spec) { return spec == kLibcamera || spec.starts_with(kLibcamera + ":"); }
bool is_simulated(const std::string& spec) { return spec == kSimulated || spec.starts_with(kSimulated + ":"); }

std::unique_ptr<hal::Camera> open_libcamera(const std::string& spec, const CameraRequest& request) {
  hal::LibcameraSettings settings;
  settings.width = request.width;
  settings.height = request.height;
  if (const io::BoardCamera* board_camera = request.board_camera) {
    settings.camera_id = board_camera->id;
    settings.formats = board_camera->formats;
    settings.frame_duration_us = board_camera->frame_duration_us;
    settings.exposure_us = board_camera->exposure_us;
    settings.analogue_gain = static_cast<float>(board_camera->analogue_gain);
    settings.buffer_count = board_camera->buffers;
  }
  if (spec.size() > kLibcamera.size()) settings.camera_id = spec.substr(kLibcamera.size() + 1);
  return std::make_unique<hal::LibcameraCamera>(settings, request.stop);
}

// Paced like the board's camera (unless "unpaced"); the scene's pipeline depth is the board's
// strobe latency, so a correct board runs in sync from the start.
std::unique_ptr<hal::Camera> open_simulated(const std::string& spec, const CameraRequest& request) {
  hal::StrobedSceneSettings settings;
  settings.width = request.width;
  settings.height = request.height;
  settings.frames = std::numeric_limits<std::uint64_t>::max();
  settings.frame_period = std::chrono::microseconds(
      request.board_camera ? request.board_camera->frame_duration_us : kSimulatedFrameDurationUs);
  settings.pipeline_depth = request.strobe_latency_frames;
  settings.stop = request.stop;
  const auto bad = [&] {
    return io::InputError("--camera " + spec + ": expected sim[:FRAMES][:unpaced][:stall-at=SEQ]");
  };
  const auto number = [&](const std::string& digits) {
    if (digits.empty() || digits.size() > 12 || digits.find_first_not_of("0123456789") != std::string::npos) throw bad();
    return std::stoull(digits);
  };
  std::size_t begin = kSimulated.size();
  bool first = true;
  while (begin < spec.size()) {
    const std::size_t end = std::min(spec.find(':', begin + 1), spec.size());
    const std::string option = spec.substr(begin + 1, end - begin - 1);
    if (option == "unpaced") {
      settings.frame_period = std::chrono::nanoseconds(0);
    } else if (option.starts_with("stall-at=")) {
      settings.stall_at_seq = number(option.substr(std::string("stall-at=").size()));
    } else if (first) {
      settings.frames = number(option);
    } else {
      throw bad();
    }
    first = false;
    begin = end;
  }
  return std::make_unique<hal::StrobedSceneCamera>(settings);
}

}  // namespace

bool is_live_camera(const std::string& spec) { return is_libcamera(spec) || is_simulated(spec); }

bool camera_drives_its_leds(const std::string& spec) { return is_simulated(spec); }

std::unique_ptr<hal::Camera> open_camera(const std::string& spec, const CameraRequest& request) {
  if (spec.starts_with(kDirPrefix) && spec.size() > kDirPrefix.size()) {
    return std::make_unique<hal::DatasetCamera>(spec.substr(kDirPrefix.size()), request.width, request.height,
                                                request.size_source);
  }
  if (is_libcamera(spec)) return open_libcamera(spec, request);
  if (is_simulated(spec)) return open_simulated(spec, request);
  throw io::InputError("--camera " + spec +
                        ": unknown camera (expected dir:DATASET, libcamera, libcamera:ID, or sim[:FRAMES][:unpaced][:stall-at=SEQ])");
}

}  // namespace irloc::firmware
