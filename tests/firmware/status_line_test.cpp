// The once-a-second status line: rates over the interval, the mount watch's tilt when it is on, and
// the capture-to-write latency of the interval's poses.

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "firmware/status_line.hpp"

namespace irloc::firmware {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;

std::string printed(const calibration::MountTilt* mount, const std::vector<std::int64_t>& latencies_ns = {}) {
  std::FILE* out = std::tmpfile();
  StatusLine line(out, std::chrono::seconds(1));
  FrameLoopStats stats;
  LatencyHistogram latency;
  latency.add(50'000'000);  // before the interval: not in its figures
  const StatusLine::Clock::time_point start{};
  line.update(stats, nullptr, 0, mount, latency, start);
  for (const std::int64_t ns : latencies_ns) latency.add(ns);
  stats.frames = 30;
  stats.pose_attempts = 15;
  stats.poses_ok = 12;
  line.update(stats, nullptr, 0, mount, latency, start + std::chrono::seconds(1));
  std::rewind(out);
  char text[512] = {};
  const std::size_t size = std::fread(text, 1, sizeof text - 1, out);
  std::fclose(out);
  return std::string(text, size);
}

TEST(StatusLine, ShowsTheMountTiltAndItsWarning) {
  EXPECT_EQ(printed(nullptr),
            "irlocd: 30.0 fps, 15.0 attempts/s, 80% ok, dropped frames 0, strobe rejected 0 (resyncs 0), serial dropped 0\n");
  calibration::MountTilt tilt;
  tilt.tilt = Eigen::Vector2d(0.0003, 0.0004);  // 0.03 deg
  EXPECT_THAT(printed(&tilt), EndsWith(", serial dropped 0, mount tilt 0.03 deg\n"));
  EXPECT_THAT(printed(&tilt), Not(HasSubstr("OFF CALIBRATION")));
  tilt.tilt = Eigen::Vector2d(0.0, 0.0175);
  tilt.warning = true;
  EXPECT_THAT(printed(&tilt), EndsWith(", mount tilt 1.00 deg OFF CALIBRATION\n"));
}

TEST(StatusLine, ShowsTheIntervalsLatencyMedianAndP99) {
  // 100 poses: 98 at 1.2 ms, one at 1.8 ms, one at 7 ms. Bins are 10 us wide, quantiles their upper edges.
  std::vector<std::int64_t> latencies(98, 1'200'000);
  latencies.push_back(1'800'000);
  latencies.push_back(7'000'000);
  EXPECT_THAT(printed(nullptr, latencies), EndsWith(", serial dropped 0, latency 1.21/1.81 ms\n"));
}

TEST(LatencyHistogram, QuantilesOverAllOrSinceACopy) {
  LatencyHistogram histogram;
  EXPECT_FALSE(histogram.quantile_ms(0.5));
  for (int i = 1; i <= 200; ++i) histogram.add(i * 100'000LL);  // 0.1 .. 20 ms
  histogram.add(-5);                                           // a clock that jumped back: not counted
  histogram.add(3'000'000'000LL);                              // beyond 100 ms: the last bin
  EXPECT_EQ(histogram.count(), 201u);
  EXPECT_NEAR(*histogram.quantile_ms(0.5), 10.11, 1e-9);
  EXPECT_NEAR(*histogram.quantile_ms(1.0), 100.0, 1e-9);
  const LatencyHistogram earlier = histogram;
  histogram.add(2'000'000);
  EXPECT_NEAR(*histogram.quantile_ms(0.5, &earlier), 2.01, 1e-9);
}

}  // namespace
}  // namespace irloc::firmware
