// A delivered frame's times from libcamera's reports (hal/linux/frame_timing.hpp): the frame time
// from SensorTimestamp and the exposure, the line time from the rolling shutter's skew.

#include "hal/linux/frame_timing.hpp"

#include <gtest/gtest.h>

namespace irloc::hal {
namespace {

TEST(FrameTiming, TheFrameTimeIsTheMiddleOfRowZerosExposure) {
  // Row 0 read out at 2 s after 1.5 ms of exposure: its exposure's middle 0.75 ms before.
  EXPECT_EQ(frame_time_ns(2'000'000'000, 1500), 1'999'250'000);
  EXPECT_EQ(frame_time_ns(2'000'000'000, 0), 2'000'000'000);
}

TEST(FrameTiming, TheSkewOverTheDeliveredRowsIsTheLineTime) {
  // The default board's mode (boards/rpi4-noir.yaml): 616 delivered rows in 23.28 ms, 37.8 us a row.
  EXPECT_EQ(line_time_from_skew_ns(616 * 37'800, 616), 37'800);
  // The IMX219's binned rows (1232) scaled by the ISP to 616: the skew spans the delivered rows.
  EXPECT_EQ(line_time_from_skew_ns(1232 * 18'900, 616), 37'800);
  // To the nearest nanosecond.
  EXPECT_EQ(line_time_from_skew_ns(1000, 3), 333);
  EXPECT_EQ(line_time_from_skew_ns(2000, 3), 667);
}

TEST(FrameTiming, NoSkewReportedIsAGlobalShutterSoTheConfiguredLineTimeHolds) {
  EXPECT_EQ(line_time_from_skew_ns(0, 616), 0);
  EXPECT_EQ(line_time_from_skew_ns(-5, 616), 0);
  EXPECT_EQ(line_time_from_skew_ns(23'284'800, 0), 0);
}

}  // namespace
}  // namespace irloc::hal
