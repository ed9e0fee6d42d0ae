#include "algo/frames/strobe_pairer.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

Frame frame(std::uint64_t seq, bool led_on) {
  Frame f;
  f.seq = seq;
  f.t_ns = static_cast<std::int64_t>(seq) * 1000;
  f.led_on = led_on;
  return f;
}

// (on seq, off seq or -1) for every pair the stream yields.
std::vector<std::pair<long, long>> pairs_of(const std::vector<Frame>& frames) {
  StrobePairer pairer;
  std::vector<std::pair<long, long>> result;
  const auto record = [&](const std::optional<StrobePair>& pair) {
    if (pair) result.emplace_back(pair->on.seq, pair->off ? static_cast<long>(pair->off->seq) : -1);
  };
  for (const Frame& f : frames) record(pairer.push(f));
  record(pairer.flush());
  return result;
}

using Pairs = std::vector<std::pair<long, long>>;

TEST(StrobePairer, PairsEachOnFrameWithThePreviousOffFrame) {
  EXPECT_EQ(pairs_of({frame(0, false), frame(1, true), frame(2, false), frame(3, true)}), (Pairs{{1, 0}, {3, 2}}));
}

TEST(StrobePairer, FallsBackToTheNextOffFrame) {
  EXPECT_EQ(pairs_of({frame(0, true), frame(1, false), frame(2, true)}), (Pairs{{0, 1}, {2, 1}}));
}

TEST(StrobePairer, NeverPairsAcrossADroppedFrame) {
  // seq 2 dropped: on-frame 3 has no adjacent off-frame before it; 4 is after it.
  EXPECT_EQ(pairs_of({frame(0, false), frame(1, true), frame(3, true), frame(4, false)}), (Pairs{{1, 0}, {3, 4}}));
  // Both neighbours of on-frame 3 dropped.
  EXPECT_EQ(pairs_of({frame(0, false), frame(1, true), frame(3, true), frame(5, true), frame(6, false)}),
            (Pairs{{1, 0}, {3, -1}, {5, 6}}));
  // Off-frame 2 dropped between two off/on neighbours that are not adjacent.
  EXPECT_EQ(pairs_of({frame(1, false), frame(3, true)}), (Pairs{{3, -1}}));
}

TEST(StrobePairer, NeverPairsTwoFramesOfTheSameState) {
  EXPECT_EQ(pairs_of({frame(0, true), frame(1, true), frame(2, true)}), (Pairs{{0, -1}, {1, -1}, {2, -1}}));
  EXPECT_EQ(pairs_of({frame(0, false), frame(1, false), frame(2, false)}), Pairs{});
}

TEST(StrobePairer, EveryOnFrameComesOutOnceWithoutAllocating) {
  StrobePairer pairer;
  int on_frames = 0;
  int pairs = 0;
  test::AllocationCounter counter;
  for (std::uint64_t seq = 0; seq < 1000; ++seq) {
    if (seq % 7 == 3) continue;  // dropped
    const bool on = seq % 2 == 1;
    on_frames += on;
    pairs += pairer.push(frame(seq, on)).has_value();
  }
  pairs += pairer.flush().has_value();
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(pairs, on_frames);
}

}  // namespace
}  // namespace irloc
