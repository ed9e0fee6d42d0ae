// The once-a-second status line: rates over the interval, and the mount watch's tilt when it is on.

#include <chrono>
#include <cstdio>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "firmware/status_line.hpp"

namespace irloc::firmware {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;

std::string printed(const calibration::MountTilt* mount) {
  std::FILE* out = std::tmpfile();
  StatusLine line(out, std::chrono::seconds(1));
  FrameLoopStats stats;
  const StatusLine::Clock::time_point start{};
  line.update(stats, nullptr, 0, mount, start);
  stats.frames = 30;
  stats.pose_attempts = 15;
  stats.poses_ok = 12;
  line.update(stats, nullptr, 0, mount, start + std::chrono::seconds(1));
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

}  // namespace
}  // namespace irloc::firmware
