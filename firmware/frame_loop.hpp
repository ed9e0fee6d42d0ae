#pragma once
// irlocd's per-frame loop: a frame from the camera, its LED label and the next strobe command,
// the frame's observers (recording), strobe pairing, the brightness check, the localizer, and
// the attempt's observers (the outputs).
// The same loop runs replay (labels from the dataset), the robot (labels from the strobe
// schedule) and software-in-the-loop (simulated camera and strobe). step() allocates nothing
// (the recorder excepted: it writes files).

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "algo/pipeline/localizer.hpp"
#include "firmware/front_end_probe.hpp"
#include "algo/source/outcome_counts.hpp"
#include "firmware/strobe_sync.hpp"
#include "hal/camera.hpp"
#include "hal/strobe.hpp"

namespace irloc::firmware {

struct FrameLoopStats {
  std::uint64_t frames = 0;
  std::uint64_t dropped_frames = 0;  // gaps in the sequence numbers
  std::uint64_t pose_attempts = 0;   // one per LED-on frame
  std::uint64_t poses_ok = 0;
  std::uint64_t poses_revised = 0;   // revisable poses sent as the next attempt revised them
  std::uint64_t unpaired = 0;        // LED-on frames without an adjacent LED-off frame
  std::uint64_t strobe_rejected = 0; // pairs whose brightness check failed: no pose computed
  StageClock::Times stage_totals;    // per pipeline stage: its total time over all attempts, ms
  double attempts_wall_ms = 0;       // Localizer::process's wall time over the same attempts, ms
  OutcomeCounts source_outcomes;     // per source: its attempts by outcome (the pairs the sources ran on)
  std::uint64_t outputs_failed = 0;  // outputs stopped by a failed write (the disk filled)
};

// Sees every frame the camera delivers, before pairing (the recorder).
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  virtual void on_frame(const Frame& frame) = 0;
  // An output that stopped after a failed write (the disk filled); the loop counts it.
  virtual bool failed() const { return false; }
};

// Sees every pose attempt, with the pair it came from: the outputs (pose CSV, pose stream) and
// the diagnostics (calibration, survey, mount watch, live view).
class AttemptObserver {
 public:
  virtual ~AttemptObserver() = default;
  // `verdict` is empty when the pair was not checked (replay, or no LED-off partner);
  // `computed` tells whether the localizer ran on it.
  virtual void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                          const PoseEstimate& estimate) = 0;
  // An output that stopped after a failed write (the disk filled); the loop counts it.
  virtual bool failed() const { return false; }
};

// Sees every attempt's pose once it is final, in the order of the frames (the pose CSV, the pose
// stream): a revisable pose (PoseEstimate::revisable) one attempt late, as the next attempt revised
// it (Localizer::revised_previous) or, where it did not, as it was.
class PoseObserver {
 public:
  virtual ~PoseObserver() = default;
  virtual void on_pose(const PoseEstimate& estimate) = 0;
  // An output that stopped after a failed write (the disk filled); the loop counts it.
  virtual bool failed() const { return false; }
};

// The observers of one loop, called in the order they were added (at most eight). An empty list
// is the null output: the loop's outputs are never null pointers.
template <typename Observer>
class ObserverList {
 public:
  void add(Observer* observer) {
    if (observer != nullptr && count_ < observers_.size()) observers_[count_++] = observer;
  }
  template <typename Call>
  void for_each(Call&& call) const {
    for (std::size_t k = 0; k < count_; ++k) call(*observers_[k]);
  }
  std::uint64_t failed() const {
    std::uint64_t count = 0;
    for (std::size_t k = 0; k < count_; ++k) count += observers_[k]->failed() ? 1 : 0;
    return count;
  }

 private:
  std::array<Observer*, 8> observers_{};
  std::size_t count_ = 0;
};

// Live strobing, a mode of the loop: each frame is labelled by the schedule (`sync`), the LEDs
// are switched through `strobe` for the frames to come and each pair must pass the brightness
// check before the sources run. A loop without it takes the camera's labels (a replayed dataset)
// and only reports the check's verdict, or has no strobe at all (outside-in). The strobe and the
// switch must outlive the loop.
struct LiveStrobing {
  hal::Strobe& strobe;  // the board's GPIO line, or the camera's own LEDs (the simulator)
  StrobeSync sync;
  // The live view's LED switch (set from its thread): false keeps the LEDs dark whatever the
  // schedule says.
  const std::atomic<bool>& leds_enabled;
};

// What one loop drives besides the camera and the localizer. They must outlive the loop.
struct FrameLoopIo {
  // Outside-in mode: every frame is a pose attempt of its own, without strobe pairing.
  bool every_frame = false;
  ObserverList<FrameObserver> frames;      // every frame (--record)
  ObserverList<AttemptObserver> attempts;  // every attempt as it is made (calibration, survey, live view, ...)
  ObserverList<PoseObserver> poses;        // every attempt's final pose, in order (--pose-csv, the pose stream)
};

class FrameLoop {
 public:
  FrameLoop(hal::Camera& camera, Localizer& localizer, const FrameLoopIo& io, std::optional<LiveStrobing> live_strobing);

  // One frame; false at the end of the stream (the last waiting pair is then flushed, and finish()).
  // The camera's DeviceLost passes through; an output's failed write does not.
  bool step();
  // Gives the pose outputs the pose held for its revision, if one is: at the end of the run.
  void finish();

  // After the camera was lost and reopened: the frame waiting for its partner is gone (its
  // pixels with it) and sequence numbers start over.
  void restart_stream();

  const FrameLoopStats& stats() const { return stats_; }
  // The front end's stage time against a memcpy of the same pairs (front_end_probe.hpp).
  std::optional<FrontEndVsMemcpy> front_end_vs_memcpy() const { return front_end_probe_.summary(); }
  // The last pair the brightness check saw was not verified (live strobing only).
  bool strobe_unverified() const { return strobe_unverified_; }
  // Live strobing's schedule and its figures; null without live strobing.
  const StrobeSync* strobe_sync() const { return live_strobing_ ? &live_strobing_->sync : nullptr; }

 private:
  void attempt(const StrobePair& pair);
  // To the pose outputs: the held pose (revised where the attempt just made revised it), then the
  // attempt's own, or holds it where it is revisable.
  void deliver_pose(const PoseEstimate& estimate);
  void send_pose(const PoseEstimate& estimate);
  std::uint64_t outputs_failed() const;
  void add_stage_times(const StageClock::Times& times);

  hal::Camera& camera_;
  Localizer& localizer_;
  FrameLoopIo io_;
  std::optional<LiveStrobing> live_strobing_;
  StrobePairer pairer_;
  FrameLoopStats stats_;
  FrontEndProbe front_end_probe_;
  bool strobe_unverified_ = false;
  std::optional<std::uint64_t> last_seq_;
  std::optional<PoseEstimate> held_pose_;
  Frame frame_;
};

}  // namespace irloc::firmware
