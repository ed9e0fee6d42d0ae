#pragma once
// irlocd's per-frame loop: a frame from the camera, its LED label and the next strobe command,
// optional recording, strobe pairing, the brightness check, the localizer, and the outputs.
// The same loop runs replay (labels from the dataset), the robot (labels from the strobe
// schedule) and software-in-the-loop (simulated camera and strobe). step() allocates nothing
// (recording excepted: it writes files).

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "algo/pipeline/localizer.hpp"
#include "firmware/front_end_probe.hpp"
#include "firmware/latency_histogram.hpp"
#include "firmware/serial_link.hpp"
#include "algo/source/outcome_counts.hpp"
#include "firmware/strobe_sync.hpp"
#include "hal/camera.hpp"
#include "io/files/pose_csv_writer.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "hal/strobe.hpp"

namespace irloc::firmware {

struct FrameLoopStats {
  std::uint64_t frames = 0;
  std::uint64_t dropped_frames = 0;  // gaps in the sequence numbers
  std::uint64_t pose_attempts = 0;   // one per LED-on frame
  std::uint64_t poses_ok = 0;
  std::uint64_t unpaired = 0;        // LED-on frames without an adjacent LED-off frame
  std::uint64_t strobe_rejected = 0; // pairs whose brightness check failed: no pose computed
  StageClock::Times stage_totals;    // per pipeline stage: its total time over all attempts, ms
  double attempts_wall_ms = 0;       // Localizer::process's wall time over the same attempts, ms
  OutcomeCounts source_outcomes;     // per source: its attempts by outcome (the pairs the sources ran on)
  std::uint64_t outputs_failed = 0;  // --record and --pose-csv stopped by a failed write (disk full)
};

// Sees every pose attempt, with the pair it came from; for tests and diagnostics.
class AttemptObserver {
 public:
  virtual ~AttemptObserver() = default;
  // `verdict` is empty when the pair was not checked (replay, or no LED-off partner);
  // `computed` tells whether the localizer ran on it.
  virtual void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                          const PoseEstimate& estimate) = 0;
};

// Several observers of one loop, called in the order they were added (at most six).
class AttemptObserverList final : public AttemptObserver {
 public:
  void add(AttemptObserver* observer) {
    if (observer != nullptr && count_ < observers_.size()) observers_[count_++] = observer;
  }
  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                  const PoseEstimate& estimate) override {
    for (std::size_t k = 0; k < count_; ++k) observers_[k]->on_attempt(pair, verdict, computed, estimate);
  }

 private:
  std::array<AttemptObserver*, 6> observers_{};
  std::size_t count_ = 0;
};

// The devices and outputs one loop uses; every pointer may be null. They must outlive the loop.
struct FrameLoopIo {
  hal::Strobe* strobe = nullptr;          // live strobing: frames are labelled by the schedule
  io::DatasetWriter* recorder = nullptr;
  io::PoseCsvWriter* pose_csv = nullptr;
  SerialLink* link = nullptr;             // the pose stream
  AttemptObserver* observer = nullptr;
  // Outside-in mode: every frame is a pose attempt of its own, without strobe pairing.
  bool every_frame = false;
  // The live view's LED switch (set from its thread): false keeps the LEDs dark whatever the
  // schedule says. Null: the LEDs follow the schedule.
  const std::atomic<bool>* leds_enabled = nullptr;
};

class FrameLoop {
 public:
  // `strobe_sync` is required with io.strobe (live strobing) and ignored without it.
  FrameLoop(hal::Camera& camera, Localizer& localizer, const FrameLoopIo& io, std::optional<StrobeSync> strobe_sync);

  // One frame; false at the end of the stream (the last waiting pair is then flushed).
  // The camera's DeviceLost passes through; a failed --record or --pose-csv write does not.
  bool step();

  // After the camera was lost and reopened: the frame waiting for its partner is gone (its
  // pixels with it) and sequence numbers start over.
  void restart_stream();

  const FrameLoopStats& stats() const { return stats_; }
  // Capture to serial write, per pose sent, where the camera knows its frames' capture on the
  // link's clock (hal::Camera::monotonic_minus_frame_clock_ns).
  const LatencyHistogram& latency() const { return latency_; }
  // The front end's stage time against a memcpy of the same pairs (front_end_probe.hpp).
  std::optional<FrontEndVsMemcpy> front_end_vs_memcpy() const { return front_end_probe_.summary(); }
  // The last pair the brightness check saw was not verified (live strobing only).
  bool strobe_unverified() const { return strobe_unverified_; }
  const StrobeSync* strobe_sync() const { return strobe_sync_ ? &*strobe_sync_ : nullptr; }

 private:
  void attempt(const StrobePair& pair);
  // A write that fails (the disk filled) stops that output with one stderr line; localization
  // and the serial stream go on.
  void record();
  void write_pose_row(const PoseEstimate& estimate);
  void add_stage_times(const StageClock::Times& times);

  hal::Camera& camera_;
  Localizer& localizer_;
  FrameLoopIo io_;
  std::optional<StrobeSync> strobe_sync_;
  StrobePairer pairer_;
  FrameLoopStats stats_;
  LatencyHistogram latency_;
  FrontEndProbe front_end_probe_;
  bool strobe_unverified_ = false;
  std::optional<std::uint64_t> last_seq_;
  Frame frame_;
};

}  // namespace irloc::firmware
