#pragma once
// A delivered frame's times from what libcamera reports with it, in the terms of a Frame
// (conventions.md, "Time of a frame and the rolling shutter"). No libcamera here: the conversions
// are tested on their own (tests/hal/linux/frame_timing_test.cpp).

#include <cstdint>

namespace irloc::hal {

// A frame's t_ns, the middle of its row 0's exposure: libcamera's SensorTimestamp is the start
// of row 0's readout, the end of that exposure (raspberrypi/picamera2#821).
std::int64_t frame_time_ns(std::int64_t sensor_timestamp_ns, std::int64_t exposure_us);

// The time between the exposures of two delivered rows from libcamera's draft control
// SensorRollingShutterSkew (the start of the first row's exposure to that of one past the last),
// which spans the delivered rows (the ISP scales the sensor's rows to them): the skew over the
// rows, to the nearest nanosecond. 0 (a global shutter: the configured line time holds) when no
// skew is reported (absent, 0 or negative) or there are no rows.
std::int64_t line_time_from_skew_ns(std::int64_t skew_ns, int delivered_rows);

}  // namespace irloc::hal
