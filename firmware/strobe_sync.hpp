#pragma once
// Keeps the live strobe in step with the frames: labels each frame with its LED state, tells the
// strobe what to do next, and checks every pair's brightness before a pose is computed from it.
// A swapped pair is sync lost: it gives no pose, is reported at once (one stderr line), and two
// in a row make the schedule resync. Allocates nothing per frame.

#include <cstdint>

#include "algo/frames/strobe_pairer.hpp"
#include "firmware/strobe_check.hpp"
#include "firmware/strobe_schedule.hpp"

namespace irloc::firmware {

struct StrobeSyncStats {
  std::uint64_t verified = 0;
  std::uint64_t swapped = 0;      // pairs whose brightness contradicted their labels
  std::uint64_t no_contrast = 0;
  std::uint64_t resyncs = 0;
};

class StrobeSync {
 public:
  StrobeSync(unsigned int latency_frames, const StrobeCheckSettings& check) : schedule_(latency_frames), check_(check) {}

  // Sets frame.led_on from the schedule and returns the LED state to command now.
  bool label(Frame& frame) const {
    frame.led_on = StrobeSchedule::lit(frame.seq);
    return schedule_.command_after(frame.seq);
  }

  // The brightness verdict on a complete pair; only `verified` pairs may give a pose.
  StrobeVerdict verify(const StrobePair& pair);

  const StrobeSyncStats& stats() const { return stats_; }
  const StrobeSchedule& schedule() const { return schedule_; }

 private:
  StrobeSchedule schedule_;
  StrobeCheckSettings check_;
  StrobeSyncStats stats_;
  unsigned int swapped_in_a_row_ = 0;
  unsigned int no_contrast_in_a_row_ = 0;
};

}  // namespace irloc::firmware
