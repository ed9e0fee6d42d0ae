#include "firmware/live/live_snapshot.hpp"

#include <algorithm>
#include <variant>

namespace irloc::firmware {
namespace {

constexpr std::int64_t kTrackSpacingNs = static_cast<std::int64_t>(1e9 / kMaxPublishRate);
constexpr auto kViewedRecently = std::chrono::seconds(2);

void copy_pixels(const GrayImageView& image, std::vector<std::uint16_t>& out) {
  std::visit(
      [&](const auto& view) {
        for (int y = 0; y < view.height(); ++y) {
          std::copy(view.row(y), view.row(y) + view.width(), out.begin() + static_cast<std::ptrdiff_t>(y) * view.width());
        }
      },
      image);
}

}  // namespace

LiveSlot::LiveSlot(int width, int height, int maxval) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  snapshot_.width = width;
  snapshot_.height = height;
  snapshot_.maxval = maxval;
  snapshot_.on.assign(pixels, 0);
  snapshot_.off.assign(pixels, 0);
}

void LiveSlot::read(LiveSnapshot& out) {
  const std::lock_guard lock(mutex_);
  out = snapshot_;
}

void LiveSlot::mark_stream_ended() {
  const std::lock_guard lock(mutex_);
  snapshot_.stream_ended = true;
  if (snapshot_.publication > 0) publication_.store(++snapshot_.publication, std::memory_order_release);
}

void LivePublisher::on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                               const PoseEstimate& estimate) {
  const LiveSlot::Clock::time_point now = LiveSlot::Clock::now();
  remember_track(estimate);
  update_frame_rate(now);
  std::unique_lock lock(slot_.mutex_, std::defer_lock);
  if (publishing_ == LivePublishing::every_attempt) {
    lock.lock();
  } else {
    if (!slot_.viewed_since(now - kViewedRecently)) return;
    if (now - last_published_ < std::chrono::duration<double>(1 / kMaxPublishRate)) return;
    if (!lock.try_lock()) return;  // the server is copying the last one: this attempt is skipped
  }
  fill(slot_.snapshot_, pair, verdict, computed, estimate);
  slot_.publication_.store(slot_.snapshot_.publication, std::memory_order_release);
  last_published_ = now;
}

void LivePublisher::remember_track(const PoseEstimate& estimate) {
  if (!estimate.ok) return;
  if (track_size_ > 0) {
    const LiveTrackPoint& newest = track_[(track_next_ + kLiveTrackPoints - 1) % kLiveTrackPoints];
    // A clock that went back (a reopened camera) starts the spacing over.
    if (estimate.t_ns >= newest.t_ns && estimate.t_ns - newest.t_ns < kTrackSpacingNs) return;
  }
  track_[track_next_] = {estimate.t_ns, estimate.x, estimate.y};
  track_next_ = (track_next_ + 1) % kLiveTrackPoints;
  track_size_ = std::min(track_size_ + 1, kLiveTrackPoints);
}

void LivePublisher::update_frame_rate(LiveSlot::Clock::time_point now) {
  if (loop_ == nullptr) return;
  const std::uint64_t frames = loop_->stats().frames;
  if (rate_since_ == LiveSlot::Clock::time_point{}) {
    rate_since_ = now;
    rate_frames_ = frames;
    return;
  }
  const double seconds = std::chrono::duration<double>(now - rate_since_).count();
  if (seconds < 1) return;
  frames_per_second_ = static_cast<double>(frames - rate_frames_) / seconds;
  rate_since_ = now;
  rate_frames_ = frames;
}

void LivePublisher::fill(LiveSnapshot& snapshot, const StrobePair& pair, std::optional<StrobeVerdict> verdict,
                         bool computed, const PoseEstimate& estimate) const {
  ++snapshot.publication;
  const bool fits = pair.on.image.index() == (pair.off ? pair.off->image.index() : pair.on.image.index()) &&
                    width_of(pair.on.image) == snapshot.width && height_of(pair.on.image) == snapshot.height &&
                    (!pair.off || (width_of(pair.off->image) == snapshot.width && height_of(pair.off->image) == snapshot.height));
  if (fits) {
    copy_pixels(pair.on.image, snapshot.on);
    snapshot.has_off = pair.off.has_value();
    if (pair.off) copy_pixels(pair.off->image, snapshot.off);
  } else {
    snapshot.has_off = false;  // a frame the localizer refuses too: the last picture stays
  }
  snapshot.estimate = estimate;
  snapshot.verdict = verdict;
  snapshot.computed = computed;
  snapshot.sources.clear();
  for (const SourceResult& result : localizer_.last_results()) {
    snapshot.sources.push_back({result.kind, result.ok, result.outcome, result.marker_id, result.confidence, result.rms_px,
                                result.observations});
  }
  snapshot.blobs.clear();
  snapshot.blobs_dropped = 0;
  if (pair.off && computed) {
    const PairAnalysis& analysis = localizer_.last_pair_analysis();
    for (const Blob& blob : analysis.blobs) snapshot.blobs.push_back({blob.x_min, blob.y_min, blob.x_max, blob.y_max});
    snapshot.blobs_dropped = analysis.blobs.dropped();
  }
  snapshot.stage_times = computed ? localizer_.last_stage_times() : StageClock::Times{};
  if (loop_ != nullptr) {
    snapshot.loop = loop_->stats();
    snapshot.strobe.reset();
    if (const StrobeSync* sync = loop_->strobe_sync()) snapshot.strobe = sync->stats();
  }
  snapshot.bad_frames = localizer_.bad_frames();
  snapshot.frames_per_second = frames_per_second_;
  snapshot.track.clear();
  const std::size_t oldest = track_size_ < kLiveTrackPoints ? 0 : track_next_;
  for (std::size_t k = 0; k < track_size_; ++k) snapshot.track.push_back(track_[(oldest + k) % kLiveTrackPoints]);
}

}  // namespace irloc::firmware
