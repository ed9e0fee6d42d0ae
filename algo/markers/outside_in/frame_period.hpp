#pragma once
// The camera's frame period as its frames' times show it, so that what the outside-in source
// counts in frames (the background's absorption) lasts the same time at 10 or 30 fps.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace irloc::outside_in {

// The shortest interval between consecutive frames among the last kIntervals: a dropped frame
// doubles one interval, the shortest is the camera's own. A clock that goes back forgets them.
class FramePeriod {
 public:
  static constexpr int kIntervals = 16;

  void add(std::int64_t t_ns) {
    if (seen_ && t_ns > last_t_ns_) {
      intervals_[static_cast<std::size_t>(next_)] = t_ns - last_t_ns_;
      next_ = (next_ + 1) % kIntervals;
      count_ = std::min(count_ + 1, kIntervals);
    } else if (seen_ && t_ns < last_t_ns_) {
      count_ = next_ = 0;
    }
    last_t_ns_ = t_ns;
    seen_ = true;
  }
  void restart() { *this = FramePeriod{}; }
  // ns; 0 until two frames have been seen.
  std::int64_t ns() const {
    if (count_ == 0) return 0;
    return *std::min_element(intervals_.begin(), intervals_.begin() + count_);
  }
  // How many frames last `seconds`, rounded, within [1, max_frames]; `fallback` until the period is known.
  int frames_in(double seconds, int fallback, int max_frames) const {
    const std::int64_t period = ns();
    if (period == 0) return fallback;
    const double frames = std::round(seconds * 1e9 / static_cast<double>(period));
    return static_cast<int>(std::clamp(frames, 1.0, static_cast<double>(max_frames)));
  }

 private:
  std::array<std::int64_t, kIntervals> intervals_{};
  std::int64_t last_t_ns_ = 0;
  int next_ = 0, count_ = 0;
  bool seen_ = false;
};

}  // namespace irloc::outside_in
