#include "firmware/camera_source.hpp"

#include "hal/input_error.hpp"
#include "hal/linux/libcamera_camera.hpp"
#include "hal/replay/dataset_camera.hpp"

namespace irloc::firmware {
namespace {

const std::string kDirPrefix = "dir:";
const std::string kLibcamera = "libcamera";

}  // namespace

bool is_live_camera(const std::string& spec) { return spec == kLibcamera || spec.starts_with(kLibcamera + ":"); }

std::unique_ptr<hal::Camera> open_camera(const std::string& spec, int width, int height, const std::string& size_source,
                                         const hal::BoardCamera* board_camera, const std::atomic<bool>* stop) {
  if (spec.starts_with(kDirPrefix) && spec.size() > kDirPrefix.size()) {
    return std::make_unique<hal::DatasetCamera>(spec.substr(kDirPrefix.size()), width, height, size_source);
  }
  if (is_live_camera(spec)) {
    hal::LibcameraSettings settings;
    settings.width = width;
    settings.height = height;
    if (board_camera) {
      settings.camera_id = board_camera->id;
      settings.formats = board_camera->formats;
      settings.frame_duration_us = board_camera->frame_duration_us;
      settings.exposure_us = board_camera->exposure_us;
      settings.analogue_gain = static_cast<float>(board_camera->analogue_gain);
      settings.buffer_count = board_camera->buffers;
    }
    if (spec.size() > kLibcamera.size()) settings.camera_id = spec.substr(kLibcamera.size() + 1);
    return std::make_unique<hal::LibcameraCamera>(settings, stop);
  }
  throw hal::InputError("--camera " + spec + ": unknown camera (expected dir:DATASET, libcamera or libcamera:ID)");
}

}  // namespace irloc::firmware
