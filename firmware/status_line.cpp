#include "firmware/status_line.hpp"

#include <stdio.h>

#include <numbers>

namespace irloc::firmware {

void StatusLine::update(const FrameLoopStats& loop, const StrobeSyncStats* strobe, std::uint64_t serial_dropped,
                        const calibration::MountTilt* mount, const LatencyHistogram& latency, Clock::time_point now) {
  if (!started_) {
    started_ = true;
    last_time_ = now;
    last_ = loop;
    last_latency_ = latency;
    return;
  }
  if (now - last_time_ < interval_) return;
  const double seconds = std::chrono::duration<double>(now - last_time_).count();
  const std::uint64_t frames = loop.frames - last_.frames;
  const std::uint64_t attempts = loop.pose_attempts - last_.pose_attempts;
  const std::uint64_t ok = loop.poses_ok - last_.poses_ok;
  const double ok_percent = attempts > 0 ? 100.0 * static_cast<double>(ok) / static_cast<double>(attempts) : 0.0;
  // One line from several calls: other threads (the serial link's, the survey map's) print their
  // lines whole, between status lines, never inside one.
  flockfile(out_);
  std::fprintf(out_,
               "irlocd: %.1f fps, %.1f attempts/s, %.0f%% ok, dropped frames %llu, strobe rejected %llu (resyncs %llu), "
               "serial dropped %llu",
               static_cast<double>(frames) / seconds, static_cast<double>(attempts) / seconds, ok_percent,
               static_cast<unsigned long long>(loop.dropped_frames), static_cast<unsigned long long>(loop.strobe_rejected),
               static_cast<unsigned long long>(strobe ? strobe->resyncs : 0), static_cast<unsigned long long>(serial_dropped));
  if (mount != nullptr) {
    std::fprintf(out_, ", mount tilt %.2f deg%s", mount->magnitude() * 180 / std::numbers::pi,
                 mount->warning ? " OFF CALIBRATION" : "");
  }
  const std::optional<double> median = latency.quantile_ms(0.5, &last_latency_);
  if (median) std::fprintf(out_, ", latency %.2f/%.2f ms", *median, *latency.quantile_ms(0.99, &last_latency_));
  std::fputc('\n', out_);
  std::fflush(out_);
  funlockfile(out_);
  last_time_ = now;
  last_ = loop;
  last_latency_ = latency;
}

}  // namespace irloc::firmware
