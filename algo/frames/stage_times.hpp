#pragma once
// Wall-clock time of each named stage of the last frame, for irlocd and irloc-sim to report.

#include <chrono>
#include <cstddef>

#include "algo/core/static_vector.hpp"

namespace irloc {

struct StageTime {
  const char* name = "";  // a string literal: lives forever
  double milliseconds = 0;
};

// Times stages back to back: each mark() closes the stage that began at the previous mark (or at
// start()).
class StageClock {
 public:
  static constexpr std::size_t kMaxStages = 16;
  using Times = StaticVector<StageTime, kMaxStages>;

  void start(Times& times) {
    times.clear();
    last_ = std::chrono::steady_clock::now();
  }
  void mark(Times& times, const char* stage) {
    const auto now = std::chrono::steady_clock::now();
    times.push_back({stage, std::chrono::duration<double, std::milli>(now - last_).count()});
    last_ = now;
  }

 private:
  std::chrono::steady_clock::time_point last_{};
};

}  // namespace irloc
