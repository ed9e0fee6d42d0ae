#pragma once
// Keeps the live strobe in step with the frames: labels each frame with its LED state, tells the
// strobe what to do next, and acts on every pair's brightness verdict (which the Localizer gives
// from its shared pass over the pair, algo/kernels/strobe_check.hpp). A swapped pair is sync
// lost: it gives no pose, is reported at once (one stderr line), and two in a row make the
// schedule resync. Allocates nothing per frame.

#include <cstdint>

#include "algo/frames/strobe_pairer.hpp"
#include "algo/kernels/strobe_check.hpp"
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
  explicit StrobeSync(unsigned int latency_frames) : schedule_(latency_frames) {}

  // Sets frame.led_on from the schedule and returns the LED state to command now.
  bool label(Frame& frame) const {
    frame.led_on = StrobeSchedule::lit(frame.seq);
    return schedule_.command_after(frame.seq);
  }

  // Counts the brightness verdict on a complete pair, reports a lost sync and resynchronises.
  void record(const StrobePair& pair, StrobeVerdict verdict);

  const StrobeSyncStats& stats() const { return stats_; }
  const StrobeSchedule& schedule() const { return schedule_; }

 private:
  StrobeSchedule schedule_;
  StrobeSyncStats stats_;
  unsigned int swapped_in_a_row_ = 0;
  unsigned int no_contrast_in_a_row_ = 0;
};

}  // namespace irloc::firmware
