#pragma once
// One camera frame as the pipeline sees it.

#include <cstdint>

#include "algo/core/image_view.hpp"

namespace irloc {

struct Frame {
  std::uint64_t seq = 0;  // capture sequence number; a gap means a dropped frame
  std::int64_t t_ns = 0;  // monotonic capture time, nanoseconds
  bool led_on = false;    // the robot's IR LEDs were on during the exposure
  GrayImageView image;    // valid until the frame source says otherwise (see StrobePairer)
  // A rolling shutter as the sensor reported it for this frame: row r is exposed at
  // t_ns + r * line_time_ns (conventions.md). 0: the camera did not say; the Localizer then uses
  // the configured camera.line_time_ns.
  std::int64_t line_time_ns = 0;
};

}  // namespace irloc
