// irlocd's front end against a memcpy of the same pairs (--stats front_end_vs_memcpy): which
// attempts are sampled, and the medians it reports.

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "algo/core/image.hpp"
#include "firmware/front_end_probe.hpp"

namespace irloc::firmware {
namespace {

StrobePair pair_of(const Image8& on, const Image8& off) {
  return StrobePair{Frame{1, 1000, true, ImageView8(on.view())}, Frame{0, 0, false, ImageView8(off.view())}};
}

StageClock::Times stages(double front_end_ms) {
  StageClock::Times times;
  times.push_back({"front_end", front_end_ms});
  times.push_back({"candidates", 5.0});  // other stages are not the front end's
  return times;
}

TEST(FrontEndProbe, ReportsNothingBeforeAPairIsSampled) {
  FrontEndProbe probe(64, 48);
  EXPECT_FALSE(probe.summary());
  const Image8 on(64, 48);
  // No LED-off frame, or a pair the Localizer refused (no front_end stage): nothing to compare.
  probe.after_attempt(StrobePair{Frame{1, 1000, true, ImageView8(on.view())}, std::nullopt}, stages(1.0));
  probe.after_attempt(pair_of(on, on), StageClock::Times{});
  EXPECT_FALSE(probe.summary());
}

TEST(FrontEndProbe, SamplesOnePairInEveryEightAndReportsMedians) {
  FrontEndProbe probe(64, 48);
  const Image8 on(64, 48), off(64, 48);
  // Attempts 0, 8 and 16 are sampled, with front ends of 3, 1 and 2 ms.
  const std::vector<double> front_end_ms = {3, 9, 9, 9, 9, 9, 9, 9, 1, 9, 9, 9, 9, 9, 9, 9, 2};
  for (const double ms : front_end_ms) probe.after_attempt(pair_of(on, off), stages(ms));
  const std::optional<FrontEndVsMemcpy> summary = probe.summary();
  ASSERT_TRUE(summary);
  EXPECT_EQ(summary->samples, 3u);
  EXPECT_DOUBLE_EQ(summary->front_end_ms, 2.0);
  EXPECT_GT(summary->memcpy_pair_ms, 0);
  EXPECT_LT(summary->memcpy_pair_ms, 1000);  // two 3 KiB copies
  EXPECT_DOUBLE_EQ(summary->ratio, summary->front_end_ms / summary->memcpy_pair_ms);
}

TEST(FrontEndProbe, SkipsAPairLargerThanTheConfiguredFrames) {
  FrontEndProbe probe(32, 24);
  const Image8 on(640, 480), off(640, 480);
  probe.after_attempt(pair_of(on, off), stages(1.0));
  EXPECT_FALSE(probe.summary());
}

}  // namespace
}  // namespace irloc::firmware
