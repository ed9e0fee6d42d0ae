#include "firmware/camera_source.hpp"

#include "hal/input_error.hpp"
#include "hal/replay/dataset_camera.hpp"

namespace irloc::firmware {

std::unique_ptr<hal::Camera> open_camera(const std::string& spec, int width, int height, const std::string& size_source) {
  const std::string dir_prefix = "dir:";
  if (spec.starts_with(dir_prefix) && spec.size() > dir_prefix.size()) {
    return std::make_unique<hal::DatasetCamera>(spec.substr(dir_prefix.size()), width, height, size_source);
  }
  throw hal::InputError("--camera " + spec + ": unknown camera (expected dir:DATASET)");
}

}  // namespace irloc::firmware
