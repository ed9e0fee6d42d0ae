#pragma once
// CPU time of the calling thread, seconds: on a machine shared with other work, wall time would
// count their share of the cores too.

#include <time.h>

namespace irloc::test {

inline double thread_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace irloc::test
