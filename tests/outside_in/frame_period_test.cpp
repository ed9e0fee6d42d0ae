// FramePeriod: the camera's frame period from its frames' times, and a time counted in frames.
#include "algo/markers/outside_in/frame_period.hpp"

#include <gtest/gtest.h>

namespace irloc::test {
namespace {

using outside_in::FramePeriod;

constexpr std::int64_t kMs = 1'000'000;

TEST(FramePeriod, CountsATimeInFramesOfTheMeasuredRate) {
  for (const int fps : {10, 15, 30}) {
    FramePeriod period;
    EXPECT_EQ(period.frames_in(1.0, 7, 255), 7) << "no frame yet: the fallback";
    period.add(0);
    EXPECT_EQ(period.frames_in(1.0, 7, 255), 7) << "one frame: no interval yet";
    for (int i = 1; i < 5; ++i) period.add(i * 1'000'000'000LL / fps);
    EXPECT_EQ(period.frames_in(1.0, 7, 255), fps);
    EXPECT_EQ(period.frames_in(0.35, 7, 255), static_cast<int>(std::lround(0.35 * fps)));
  }
}

TEST(FramePeriod, ADroppedFrameDoesNotLengthenThePeriod) {
  FramePeriod period;
  const std::int64_t times[] = {0, 33 * kMs, 67 * kMs, 133 * kMs, 167 * kMs};  // 100 ms: one dropped
  for (const std::int64_t t : times) period.add(t);
  EXPECT_EQ(period.ns(), 33 * kMs);
}

TEST(FramePeriod, FollowsARateChangeOnceItsIntervalsHaveLeft) {
  FramePeriod period;
  std::int64_t t = 0;
  for (int i = 0; i < 20; ++i) period.add(t += 33 * kMs);
  EXPECT_EQ(period.ns(), 33 * kMs);
  for (int i = 0; i < FramePeriod::kIntervals; ++i) period.add(t += 100 * kMs);
  EXPECT_EQ(period.ns(), 100 * kMs);
}

TEST(FramePeriod, AClockThatGoesBackForgetsTheIntervals) {
  FramePeriod period;
  period.add(1000 * kMs);
  period.add(1010 * kMs);
  period.add(10 * kMs);  // a camera reopened: its clock starts again
  EXPECT_EQ(period.ns(), 0);
  period.add(110 * kMs);
  EXPECT_EQ(period.ns(), 100 * kMs);
}

TEST(FramePeriod, ClampsTheCountToItsRange) {
  FramePeriod period;
  period.add(0);
  period.add(1 * kMs);  // 1000 fps
  EXPECT_EQ(period.frames_in(1.0, 7, 255), 255);
  EXPECT_EQ(period.frames_in(0.0001, 7, 255), 1);
}

}  // namespace
}  // namespace irloc::test
