// OutcomeCounts: each source's attempts by outcome text, for irlocd --stats; and each source's
// outcome enum, whose texts those are.

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "algo/markers/dot/dot_outcome.hpp"
#include "algo/markers/led/led_outcome.hpp"
#include "algo/markers/outside_in/outside_in_outcome.hpp"
#include "algo/markers/square/square_outcome.hpp"
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

// Every outcome of a source, `found` to `last`, through SourceResult::set_outcome: its text is
// `found` for found, otherwise a reason of its own (no two alike, none missing).
template <typename Outcome>
void expect_distinct_texts(Outcome last) {
  std::set<std::string_view> texts;
  for (int k = 0; k <= static_cast<int>(last); ++k) {
    SourceResult result;
    result.set_outcome(static_cast<Outcome>(k));
    const std::string_view text = result.outcome;
    EXPECT_EQ(text, to_string(static_cast<Outcome>(k)));
    EXPECT_TRUE(!text.empty() && text != "?") << k;
    EXPECT_TRUE(texts.insert(text).second) << text;
  }
  SourceResult found;
  found.set_outcome(Outcome::found);
  EXPECT_STREQ(found.outcome, "found");
}

TEST(SourceOutcomes, EachSourceSetsOneTextPerOutcome) {
  expect_distinct_texts(dot::DotOutcome::low_confidence);
  expect_distinct_texts(square::SquareOutcome::unidentified);
  expect_distinct_texts(led::LedOutcome::too_uncertain);
  expect_distinct_texts(outside_in::OutsideInOutcome::not_explained);
}

}  // namespace
}  // namespace irloc
