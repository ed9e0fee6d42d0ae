#pragma once
// Where the libcamera API differs between the versions the backend builds against (Debian 12's
// 0.0.3, bookworm-backports' 0.3.2, Debian 13's 0.4.0, make check-backends; Raspberry Pi OS's
// 0.5): here and nowhere else. A pixel format a version does not know (R16 before 0.1) is found
// at run time (PixelFormat::fromString), not here.

#include <cstdint>
#include <limits>

#include <libcamera/control_ids.h>
#include <libcamera/controls.h>
#include <libcamera/framebuffer.h>
#include <libcamera/request.h>
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

// What a completed request says of its frame.
struct CompletedFrame {
  bool delivered = false;         // a whole frame (not cancelled, not flagged broken)
  std::uint32_t sequence = 0;     // the sensor's frame count (a gap is a dropped frame)
  std::int64_t frame_start_ns = 0;  // CLOCK_MONOTONIC: SensorTimestamp, else the buffer's timestamp
};

// A pipeline handler fills each completed buffer's FrameMetadata, except libcamera 0.4's virtual
// one (make test-vm's camera; libcamera bug 245, fixed in 0.5.0), which leaves it as it was:
// uninitialised at first, then whatever was there. So each buffer's metadata is marked before its
// request is queued (the application owns it then: the object is not const, only the accessor),
// and a buffer still marked when it completes is described by its request: its status, its
// sequence number in the camera's queue (no drop can show there) and SensorTimestamp.
constexpr std::uint32_t kUnfilledSequence = std::numeric_limits<std::uint32_t>::max();

inline void mark_metadata_unfilled(const libcamera::FrameBuffer& buffer) {
  auto& metadata = const_cast<libcamera::FrameMetadata&>(buffer.metadata());
  metadata.status = libcamera::FrameMetadata::FrameSuccess;
  metadata.sequence = kUnfilledSequence;
  metadata.timestamp = 0;
}

inline CompletedFrame completed_frame(libcamera::Request& request, const libcamera::FrameBuffer& buffer) {
  const libcamera::FrameMetadata& metadata = buffer.metadata();
  const bool unfilled = metadata.sequence == kUnfilledSequence && metadata.timestamp == 0;
  CompletedFrame frame;
  frame.delivered = request.status() == libcamera::Request::RequestComplete &&
                    metadata.status == libcamera::FrameMetadata::FrameSuccess;
  frame.sequence = unfilled ? request.sequence() : metadata.sequence;
  frame.frame_start_ns = request.metadata().get(libcamera::controls::SensorTimestamp)
                             .value_or(static_cast<std::int64_t>(metadata.timestamp));
  return frame;
}

}  // namespace irloc::hal
