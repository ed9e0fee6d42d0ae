#pragma once
// A camera's setup controls (exposure, analogue gain, frame duration), for a person aiming and
// tuning the camera through irlocd's live view. Set from another thread than the frame loop's;
// the camera applies a request at a later frame and never blocks its next() for it.

#include <array>
#include <optional>
#include <string_view>

namespace irloc::hal {

enum class CameraControl { exposure_us, analogue_gain, frame_duration_us };

inline constexpr std::array<CameraControl, 3> kCameraControls = {CameraControl::exposure_us, CameraControl::analogue_gain,
                                                                 CameraControl::frame_duration_us};

// The control's name in the live view's JSON and in the camera settings file (docs/hardware.md).
constexpr std::string_view to_string(CameraControl control) {
  switch (control) {
    case CameraControl::exposure_us: return "exposure_us";
    case CameraControl::analogue_gain: return "analogue_gain";
    case CameraControl::frame_duration_us: return "frame_duration_us";
  }
  return "?";
}

inline std::optional<CameraControl> camera_control_named(std::string_view name) {
  for (const CameraControl control : kCameraControls) {
    if (to_string(control) == name) return control;
  }
  return std::nullopt;
}

// The closed range a control accepts, in its unit (microseconds, or the gain factor).
struct ControlRange {
  double min = 0;
  double max = 0;
};

class CameraControls {
 public:
  virtual ~CameraControls() = default;

  // The range of `control`, or nothing when this camera does not have it.
  virtual std::optional<ControlRange> range(CameraControl control) const = 0;
  // Asks for `value` (within range(control): the caller checks) from a later frame on. Any
  // thread; allocates nothing and returns at once.
  virtual void request(CameraControl control, double value) = 0;
  // The value in effect for the last frame delivered (the requested one until the first frame).
  // Any thread.
  virtual double current(CameraControl control) const = 0;
};

}  // namespace irloc::hal
