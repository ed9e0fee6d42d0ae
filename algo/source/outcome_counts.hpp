#pragma once
// How often each pose source ended its attempts with each outcome ("found", or why not), over a
// run: what irlocd --stats reports per source (docs/formats.md). Generic over the sources: a
// source declares its outcomes as an enum with its text (e.g. LedOutcome, SquareOutcome) and sets
// one per attempt (SourceResult::set_outcome); this counts the texts per SourceKind.
//
// Fixed capacity, sized once; add() allocates nothing. A pair beyond the capacity is counted in
// dropped(), not lost silently.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "algo/core/static_vector.hpp"
#include "algo/source/source_kind.hpp"
#include "algo/source/source_result.hpp"

namespace irloc {

struct OutcomeCount {
  SourceKind source = SourceKind::dot;
  const char* outcome = "";  // the source's string literal
  std::uint64_t count = 0;
};

class OutcomeCounts {
 public:
  static constexpr std::size_t kCapacity = 96;  // every outcome of every source, with room to spare

  // One attempt's result of one source. A result without an outcome (the source did not run) is
  // not counted.
  void add(const SourceResult& result) {
    if (result.outcome == nullptr || result.outcome[0] == '\0') return;
    for (OutcomeCount& entry : counts_) {
      if (entry.source == result.kind && std::strcmp(entry.outcome, result.outcome) == 0) {
        ++entry.count;
        return;
      }
    }
    if (!counts_.push_back({result.kind, result.outcome, 1})) ++dropped_;
  }

  // In the order first seen.
  std::span<const OutcomeCount> counts() const { return {counts_.begin(), counts_.size()}; }
  std::uint64_t dropped() const { return dropped_; }

 private:
  StaticVector<OutcomeCount, kCapacity> counts_;
  std::uint64_t dropped_ = 0;
};

}  // namespace irloc
