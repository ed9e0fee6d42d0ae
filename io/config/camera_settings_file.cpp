#include "io/config/camera_settings_file.hpp"

#include "io/config/yaml_reader.hpp"
#include "io/files/output_file.hpp"

namespace irloc::io {

CameraSettings read_camera_settings(const std::filesystem::path& path, const hal::CameraControls* controls) {
  YamlMap root(load_yaml_file(path), path.string(), "");
  CameraSettings settings;
  for (const hal::CameraControl control : hal::kCameraControls) {
    const std::string key(to_string(control));
    if (!root.has(key)) continue;
    const std::optional<hal::ControlRange> range = controls ? controls->range(control) : std::nullopt;
    if (!range) root.fail_key(key, "this camera has no such control");
    settings[control] = root.number(key, Range{range->min, range->max});
  }
  settings.leds = root.boolean("leds", true);
  root.reject_unknown_keys();
  return settings;
}

std::string camera_settings_yaml(const CameraSettings& settings) {
  std::string text = "# irlocd camera settings, saved from the live view (docs/hardware.md)\n";
  for (const hal::CameraControl control : hal::kCameraControls) {
    if (settings[control]) text += std::string(to_string(control)) + ": " + number_text(*settings[control]) + "\n";
  }
  text += std::string("leds: ") + (settings.leds ? "true" : "false") + "\n";
  return text;
}

void write_camera_settings(const std::filesystem::path& path, const CameraSettings& settings) {
  replace_file_atomically(path, camera_settings_yaml(settings), 0644, "the camera settings");
}

}  // namespace irloc::io
