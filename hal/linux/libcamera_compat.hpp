#pragma once
// Where the libcamera API differs between the versions the backend builds against (Debian 12's
// 0.0.3, bookworm-backports' 0.3.2, Debian 13's 0.4.0, make check-backends; Raspberry Pi OS's
// 0.5): here and nowhere else. A pixel format a version does not know (R16 before 0.1) is found
// at run time (PixelFormat::fromString), not here.

#include <libcamera/control_ids.h>
#include <libcamera/controls.h>
#include <libcamera/version.h>

namespace irloc::hal {

// Manual exposure and gain among the start controls, for the controls the camera lists (`known`):
// AeEnable = false before libcamera 0.5; ExposureTimeMode and AnalogueGainMode = Manual from 0.5.
inline void set_manual_exposure(libcamera::ControlList& controls, const libcamera::ControlInfoMap& known) {
#if LIBCAMERA_VERSION_MAJOR > 0 || LIBCAMERA_VERSION_MINOR >= 5
  if (known.count(&libcamera::controls::ExposureTimeMode)) {
    controls.set(libcamera::controls::ExposureTimeMode, libcamera::controls::ExposureTimeModeManual);
  }
  if (known.count(&libcamera::controls::AnalogueGainMode)) {
    controls.set(libcamera::controls::AnalogueGainMode, libcamera::controls::AnalogueGainModeManual);
  }
#else
  if (known.count(&libcamera::controls::AeEnable)) controls.set(libcamera::controls::AeEnable, false);
#endif
}

}  // namespace irloc::hal
