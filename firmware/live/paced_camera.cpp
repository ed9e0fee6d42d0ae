#include "firmware/live/paced_camera.hpp"

#include <algorithm>
#include <thread>

namespace irloc::firmware {

bool PacedCamera::next(Frame& frame) {
  if (!camera_->next(frame)) return false;
  if (!first_t_ns_ || frame.t_ns < *first_t_ns_) {  // the first frame, or a clock that went back
    first_t_ns_ = frame.t_ns;
    started_ = Clock::now();
    return true;
  }
  const Clock::time_point due = started_ + std::chrono::nanoseconds(frame.t_ns - *first_t_ns_);
  // In slices, so that a stop request is seen within 50 ms.
  while (Clock::now() < due && !(stop_ && stop_->load())) {
    std::this_thread::sleep_until(std::min(due, Clock::now() + std::chrono::milliseconds(50)));
  }
  return true;
}

std::optional<std::int64_t> PacedCamera::monotonic_minus_frame_clock_ns() const {
  if (!first_t_ns_) return std::nullopt;
  return std::chrono::duration_cast<std::chrono::nanoseconds>(started_.time_since_epoch()).count() - *first_t_ns_;
}

}  // namespace irloc::firmware
