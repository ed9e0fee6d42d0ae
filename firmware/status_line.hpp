#pragma once
// The once-a-second status line irlocd prints on stderr while running on a robot:
//   irlocd: 30.0 fps, 15.0 attempts/s, 93% ok, dropped frames 0, strobe rejected 1 (resyncs 0), serial dropped 0,
//   mount tilt 0.03 deg, latency 1.21/1.85 ms
// Rates are over the last interval; counts are totals since start; latency is the median and the
// 99th percentile of capture to serial write over the poses sent in the last interval. The mount's tilt (with the
// watch on) reads "mount tilt 1.02 deg OFF CALIBRATION" while its warning holds. Allocates nothing.

#include <chrono>
#include <cstdint>
#include <cstdio>

#include "algo/calibration/mount_tilt_watch.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/latency_histogram.hpp"

namespace irloc::firmware {

class StatusLine {
 public:
  using Clock = std::chrono::steady_clock;

  StatusLine(std::FILE* out, Clock::duration interval) : out_(out), interval_(interval) {}

  // Prints a line when `interval` has passed since the last one (or since the first call).
  void update(const FrameLoopStats& loop, const StrobeSyncStats* strobe, std::uint64_t serial_dropped,
              const calibration::MountTilt* mount, const LatencyHistogram& latency, Clock::time_point now);

 private:
  std::FILE* out_;
  Clock::duration interval_;
  bool started_ = false;
  Clock::time_point last_time_;
  FrameLoopStats last_;
  LatencyHistogram last_latency_;
};

}  // namespace irloc::firmware
