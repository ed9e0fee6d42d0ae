// OutcomeCounts: each source's attempts by outcome text, for irlocd --stats.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "algo/source/outcome_counts.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

SourceResult result_of(SourceKind kind, const char* outcome) {
  SourceResult result;
  result.clear(kind);
  result.outcome = outcome;
  return result;
}

TEST(OutcomeCounts, CountsEachSourcesOutcomesApartByTextWithoutAllocating) {
  OutcomeCounts counts;
  // The same text from two places (not the same pointer) is one outcome.
  const std::string ambiguous = "ambiguous";
  const SourceResult led_found = result_of(SourceKind::led, "found");
  const SourceResult led_ambiguous = result_of(SourceKind::led, ambiguous.c_str());
  const SourceResult dot_found = result_of(SourceKind::dot, "found");
  const SourceResult not_run = result_of(SourceKind::square, "");
  {
    const test::AllocationCounter allocations;
    for (int k = 0; k < 3; ++k) counts.add(led_found);
    counts.add(led_ambiguous);
    counts.add(result_of(SourceKind::led, "ambiguous"));
    counts.add(dot_found);
    counts.add(not_run);
    EXPECT_EQ(allocations.count(), 0u);
  }
  ASSERT_EQ(counts.counts().size(), 3u);
  EXPECT_EQ(counts.counts()[0].source, SourceKind::led);
  EXPECT_STREQ(counts.counts()[0].outcome, "found");
  EXPECT_EQ(counts.counts()[0].count, 3u);
  EXPECT_STREQ(counts.counts()[1].outcome, "ambiguous");
  EXPECT_EQ(counts.counts()[1].count, 2u);
  EXPECT_EQ(counts.counts()[2].source, SourceKind::dot);
  EXPECT_EQ(counts.counts()[2].count, 1u);
  EXPECT_EQ(counts.dropped(), 0u);
}

TEST(OutcomeCounts, OutcomesBeyondTheCapacityAreCountedAsDropped) {
  OutcomeCounts counts;
  std::vector<std::string> texts;
  for (std::size_t k = 0; k < OutcomeCounts::kCapacity + 2; ++k) texts.push_back("outcome " + std::to_string(k));
  for (const std::string& text : texts) counts.add(result_of(SourceKind::led, text.c_str()));
  EXPECT_EQ(counts.counts().size(), OutcomeCounts::kCapacity);
  EXPECT_EQ(counts.dropped(), 2u);
}

}  // namespace
}  // namespace irloc
