#pragma once
// Which frames the IR LEDs light. Frame `seq` (the camera's sequence number, which counts dropped
// frames too) is lit when seq is even, so a dropped frame never shifts the pattern.
// The line is switched when a frame arrives, for the frame `latency` later: the frames in between
// are already exposing. The true latency is the sensor pipeline's depth; when the board's value
// has the wrong parity every pair comes out swapped (strobe_check.hpp), and resync() adds one
// frame to the latency, which puts the commands back in step with the labels.

#include <cstdint>

namespace irloc::firmware {

class StrobeSchedule {
 public:
  explicit StrobeSchedule(unsigned int latency_frames) : latency_(latency_frames) {}

  static bool lit(std::uint64_t seq) { return (seq & 1u) == 0; }
  // The LED state to command once frame `seq` has arrived.
  bool command_after(std::uint64_t seq) const { return lit(seq + latency_); }
  void resync() { latency_ = latency_ % 2 == 0 ? latency_ + 1 : latency_ - 1; }

  unsigned int latency_frames() const { return latency_; }

 private:
  unsigned int latency_;
};

}  // namespace irloc::firmware
