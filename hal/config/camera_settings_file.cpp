#include "hal/config/camera_settings_file.hpp"

#include "hal/config/yaml_reader.hpp"
#include "hal/files/output_file.hpp"

namespace irloc::hal {

CameraSettings read_camera_settings(const std::filesystem::path& path, const CameraControls* controls) {
  YamlMap root(load_yaml_file(path), path.string(), "");
  CameraSettings settings;
  for (const CameraControl control : kCameraControls) {
    const std::string key(to_string(control));
    if (!root.has(key)) continue;
    const std::optional<ControlRange> range = controls ? controls->range(control) : std::nullopt;
    if (!range) root.fail_key(key, "this camera has no such control");
    settings[control] = root.number(key, Range{range->min, range->max});
  }
  settings.leds = root.boolean("leds", true);
  root.reject_unknown_keys();
  return settings;
}

std::string camera_settings_yaml(const CameraSettings& settings) {
  std::string text = "# irlocd camera settings, saved from the live view (docs/hardware.md)\n";
  for (const CameraControl control : kCameraControls) {
    if (settings[control]) text += std::string(to_string(control)) + ": " + number_text(*settings[control]) + "\n";
  }
  text += std::string("leds: ") + (settings.leds ? "true" : "false") + "\n";
  return text;
}

void write_camera_settings(const std::filesystem::path& path, const CameraSettings& settings) {
  replace_file_atomically(path, camera_settings_yaml(settings), 0644, "the camera settings");
}

}  // namespace irloc::hal
