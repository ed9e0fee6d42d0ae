#include "hal/linux/frame_timing.hpp"

namespace irloc::hal {

std::int64_t frame_time_ns(std::int64_t sensor_timestamp_ns, std::int64_t exposure_us) {
  return sensor_timestamp_ns - exposure_us * 1000 / 2;
}

std::int64_t line_time_from_skew_ns(std::int64_t skew_ns, int delivered_rows) {
  if (skew_ns <= 0 || delivered_rows <= 0) return 0;
  return (skew_ns + delivered_rows / 2) / delivered_rows;
}

}  // namespace irloc::hal
