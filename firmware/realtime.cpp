#include "firmware/realtime.hpp"

#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "io/input_error.hpp"

namespace irloc::firmware {

void enter_realtime(int priority) {
  const std::string what = "realtime priority " + std::to_string(priority);
  if (priority < sched_get_priority_min(SCHED_FIFO) || priority > sched_get_priority_max(SCHED_FIFO)) {
    throw io::InputError(what + ": out of range 1..99");
  }
  sched_param parameters{};
  parameters.sched_priority = priority;
  if (sched_setscheduler(0, SCHED_FIFO, &parameters) != 0) {
    throw io::InputError(what + ": cannot switch to SCHED_FIFO: " + std::strerror(errno) +
                          " (run as root or grant CAP_SYS_NICE)");
  }
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    throw io::InputError(what + ": cannot lock memory: " + std::strerror(errno) + " (grant CAP_IPC_LOCK)");
  }
}

}  // namespace irloc::firmware
