#pragma once
// What the live view shows of one pose attempt, and the slot through which the frame loop hands
// it to the live view's server thread.
//
// The frame loop publishes (LivePublisher, an AttemptObserver) only while somebody looked at the
// view within the last two seconds, at most kMaxPublishRate times a second, and only when the
// slot is free: it tries the slot's lock and skips the attempt when the server holds it. Every
// buffer is sized at start-up, so publishing allocates nothing and never waits.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

#include "algo/kernels/strobe_check.hpp"
#include "algo/pipeline/localizer.hpp"
#include "firmware/frame_loop.hpp"
#include "firmware/strobe_sync.hpp"

namespace irloc::firmware {

// The strobe verdict as the live view and the annotated frames name it.
constexpr const char* strobe_verdict_name(StrobeVerdict verdict) {
  switch (verdict) {
    case StrobeVerdict::verified: return "verified";
    case StrobeVerdict::swapped: return "swapped";
    case StrobeVerdict::no_contrast: return "no_contrast";
  }
  return "?";
}

// One source's part of the attempt: its outcome ("found", or why not) and the points it measured.
struct LiveSourceAttempt {
  SourceKind kind = SourceKind::dot;
  bool ok = false;
  const char* outcome = "";  // SourceResult::outcome: a string literal
  int marker_id = -1;
  double confidence = 0;
  double rms_px = 0;
  PointObservationList observations;
};

// A blob of the pair's shared pass (on - off above its threshold): its bounding box, px.
struct LiveBlob {
  int x_min = 0, y_min = 0, x_max = 0, y_max = 0;
};

struct LiveTrackPoint {
  std::int64_t t_ns = 0;  // the pose's frame time
  double x = 0, y = 0;    // W, metres
};

inline constexpr double kMaxPublishRate = 10;            // snapshots a second at most
inline constexpr std::size_t kLiveTrackPoints = 600;     // a minute of poses at kMaxPublishRate

struct LiveSnapshot {
  std::uint64_t publication = 0;  // counts publications; 0: nothing published yet
  int width = 0, height = 0;
  int maxval = 255;               // the camera's largest pixel value
  std::vector<std::uint16_t> on, off;  // width * height each, sized at start-up
  bool has_off = false;
  PoseEstimate estimate;          // seq and t_ns are the LED-on frame's
  std::optional<StrobeVerdict> verdict;  // empty when the pair was not checked
  bool computed = false;          // the localizer's sources ran on the pair
  StaticVector<LiveSourceAttempt, kMaxFusedSources> sources;
  StaticVector<LiveBlob, kMaxBlobs> blobs;
  std::uint32_t blobs_dropped = 0;  // blobs beyond the pass's capacity
  StageClock::Times stage_times;    // of this attempt, ms
  FrameLoopStats loop;              // counters since start
  std::optional<StrobeSyncStats> strobe;  // with live strobing
  std::uint64_t bad_frames = 0;     // pairs the localizer refused (size or depth)
  double frames_per_second = 0;     // camera frames over the last second or so
  StaticVector<LiveTrackPoint, kLiveTrackPoints> track;  // the last minute's poses, oldest first
  bool stream_ended = false;        // a replay reached its end: this is its last attempt
};

class LiveSlot {
 public:
  using Clock = std::chrono::steady_clock;

  LiveSlot(int width, int height, int maxval);

  // Server thread: somebody looks at the view now (publishing goes on for two seconds).
  void mark_viewed(Clock::time_point now) { last_viewed_ns_.store(now.time_since_epoch().count(), std::memory_order_relaxed); }
  bool viewed_since(Clock::time_point since) const {
    return last_viewed_ns_.load(std::memory_order_relaxed) >= since.time_since_epoch().count();
  }
  // Server thread: copies the latest snapshot into `out` (whose buffers are reused), blocking
  // the frame loop's publishing (never the frame loop) for the copy.
  void read(LiveSnapshot& out);
  // Any thread: the publication number of the latest snapshot (LiveSnapshot::publication).
  std::uint64_t publication() const { return publication_.load(std::memory_order_acquire); }
  // Frame loop: the stream ended (a replay's end); the last snapshot stays on view.
  void mark_stream_ended();

 private:
  friend class LivePublisher;
  std::mutex mutex_;
  LiveSnapshot snapshot_;
  std::atomic<std::uint64_t> publication_{0};
  std::atomic<Clock::rep> last_viewed_ns_{std::numeric_limits<Clock::rep>::min()};
};

enum class LivePublishing {
  when_viewed,    // the live view: only while viewed, rate-limited, skipped when the slot is busy
  every_attempt,  // offline annotation (--annotate): every attempt, waiting for the slot
};

// Publishes pose attempts into a LiveSlot from the frame loop. on_attempt() allocates nothing.
class LivePublisher final : public AttemptObserver {
 public:
  LivePublisher(LiveSlot& slot, const Localizer& localizer, LivePublishing publishing = LivePublishing::when_viewed)
      : slot_(slot), localizer_(localizer), publishing_(publishing) {}

  // The loop whose counters the snapshots carry (made after its observers).
  void watch(const FrameLoop& loop) { loop_ = &loop; }

  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                  const PoseEstimate& estimate) override;

 private:
  void remember_track(const PoseEstimate& estimate);
  void update_frame_rate(LiveSlot::Clock::time_point now);
  void fill(LiveSnapshot& snapshot, const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
            const PoseEstimate& estimate) const;

  LiveSlot& slot_;
  const Localizer& localizer_;
  LivePublishing publishing_;
  const FrameLoop* loop_ = nullptr;
  std::array<LiveTrackPoint, kLiveTrackPoints> track_{};  // ring, oldest at track_next_ once full
  std::size_t track_next_ = 0, track_size_ = 0;
  LiveSlot::Clock::time_point last_published_{};
  LiveSlot::Clock::time_point rate_since_{};
  std::uint64_t rate_frames_ = 0;
  double frames_per_second_ = 0;
};

}  // namespace irloc::firmware
