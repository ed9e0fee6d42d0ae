#pragma once
// The camera settings file (docs/hardware.md): the setup controls saved from irlocd's live view,
// applied at the next start.
//
//   exposure_us: 3000        # each control optional; ranges are the camera's (hal::CameraControls)
//   analogue_gain: 2.5
//   frame_duration_us: 33333
//   leds: true               # the LED strobe on (default) or off

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "hal/camera_controls.hpp"

namespace irloc::io {

struct CameraSettings {
  std::array<std::optional<double>, hal::kCameraControls.size()> values;  // by hal::CameraControl
  bool leds = true;

  std::optional<double>& operator[](hal::CameraControl control) { return values[static_cast<std::size_t>(control)]; }
  const std::optional<double>& operator[](hal::CameraControl control) const { return values[static_cast<std::size_t>(control)]; }
};

// Reads `path`, checking each value against `controls`' range (null: a camera without controls,
// for which any control in the file is an error). Throws InputError "FILE:LINE: FIELD: PROBLEM".
CameraSettings read_camera_settings(const std::filesystem::path& path, const hal::CameraControls* controls);

std::string camera_settings_yaml(const CameraSettings& settings);

// Replaces `path` atomically (output_file.hpp); throws InputError naming it.
void write_camera_settings(const std::filesystem::path& path, const CameraSettings& settings);

}  // namespace irloc::io
