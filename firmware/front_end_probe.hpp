#pragma once
// The front end's stage time against a memcpy of the same frame pair, on the machine irlocd runs
// on (--stats: front_end_vs_memcpy), so that a user can read the front end's cost against the
// memory speed of the robot: every kEvery-th pair the Localizer computed is also copied once, right
// after its attempt, into a buffer made at start-up. Reported as medians of the last kSamples.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "algo/frames/stage_times.hpp"
#include "algo/frames/strobe_pairer.hpp"

namespace irloc::firmware {

struct FrontEndVsMemcpy {
  std::uint64_t samples = 0;  // pairs copied over the run
  double front_end_ms = 0;    // median of those attempts' front_end stages (relabellings included)
  double memcpy_pair_ms = 0;  // median time to copy both frames of the same pairs
  double ratio = 0;           // front_end_ms / memcpy_pair_ms
};

// The attempt's front_end stages (the Localizer's shared pass and any relabelling a source asked
// for, which the dot source names front_end too), ms.
double front_end_total_ms(const StageClock::Times& times);

class FrontEndProbe {
 public:
  static constexpr std::uint64_t kEvery = 8;
  static constexpr std::size_t kSamples = 256;

  // The only allocation: room for two width x height frames of 16-bit pixels.
  FrontEndProbe(int width, int height);

  // After each attempt the Localizer computed, with its stage times. Allocates nothing.
  void after_attempt(const StrobePair& pair, const StageClock::Times& times);

  // Empty before the first sample.
  std::optional<FrontEndVsMemcpy> summary() const;

 private:
  std::vector<std::byte> copy_;
  std::uint64_t attempts_ = 0;
  std::uint64_t samples_ = 0;
  std::array<double, kSamples> front_end_ms_{};
  std::array<double, kSamples> memcpy_ms_{};
};

}  // namespace irloc::firmware
