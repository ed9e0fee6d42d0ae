#include "firmware/frame_loop.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string_view>
#include <utility>


namespace irloc::firmware {

FrameLoop::FrameLoop(hal::Camera& camera, Localizer& localizer, const FrameLoopIo& io,
                     std::optional<LiveStrobing> live_strobing)
    : camera_(camera),
      localizer_(localizer),
      io_(io),
      live_strobing_(std::move(live_strobing)),
      front_end_probe_(camera.width(), camera.height()) {}

bool FrameLoop::step() {
  if (!camera_.next(frame_)) {
    if (const std::optional<StrobePair> pair = pairer_.flush()) attempt(*pair);
    finish();
    return false;
  }
  ++stats_.frames;
  if (last_seq_ && frame_.seq > *last_seq_ + 1) stats_.dropped_frames += frame_.seq - *last_seq_ - 1;
  last_seq_ = frame_.seq;
  if (live_strobing_) {
    const bool lit = live_strobing_->sync.label(frame_);
    live_strobing_->strobe.set_led(lit && live_strobing_->leds_enabled.load(std::memory_order_relaxed));
  }
  io_.frames.for_each([&](FrameObserver& observer) { observer.on_frame(frame_); });
  stats_.outputs_failed = outputs_failed();
  if (io_.every_frame) {
    attempt(StrobePair{frame_, std::nullopt});
  } else if (const std::optional<StrobePair> pair = pairer_.push(frame_)) {
    attempt(*pair);
  }
  return true;
}

void FrameLoop::restart_stream() {
  pairer_ = StrobePairer();
  last_seq_.reset();
}

void FrameLoop::attempt(const StrobePair& pair) {
  ++stats_.pose_attempts;
  if (!pair.off && !io_.every_frame) ++stats_.unpaired;
  // Live strobing: the Localizer's verdict from its pass over the pair; a pair that is not
  // verified gives none without running the sources.
  const bool checked = live_strobing_ && pair.off;
  const auto start = std::chrono::steady_clock::now();
  const PoseEstimate estimate = localizer_.process(pair, checked ? StrobeGate::require_verified : StrobeGate::report);
  const double wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::optional<StrobeVerdict> verdict;
  if (checked) {
    verdict = localizer_.last_strobe_verdict();
    live_strobing_->sync.record(pair, *verdict);
    strobe_unverified_ = *verdict != StrobeVerdict::verified;
  }
  const bool compute = !verdict || *verdict == StrobeVerdict::verified;
  if (compute) {
    add_stage_times(localizer_.last_stage_times());
    stats_.attempts_wall_ms += wall_ms;
    front_end_probe_.after_attempt(pair, localizer_.last_stage_times());
    for (const SourceResult& result : localizer_.last_results()) stats_.source_outcomes.add(result);
  } else {
    ++stats_.strobe_rejected;
  }
  if (estimate.ok) ++stats_.poses_ok;
  io_.attempts.for_each([&](AttemptObserver& observer) { observer.on_attempt(pair, verdict, compute, estimate); });
  deliver_pose(estimate);
  stats_.outputs_failed = outputs_failed();
}

void FrameLoop::deliver_pose(const PoseEstimate& estimate) {
  if (held_pose_) {
    const std::optional<PoseEstimate>& revised = localizer_.revised_previous();
    if (revised) ++stats_.poses_revised;
    send_pose(revised ? *revised : *held_pose_);
    held_pose_.reset();
  }
  if (estimate.revisable) held_pose_ = estimate;
  else send_pose(estimate);
}

void FrameLoop::send_pose(const PoseEstimate& estimate) {
  io_.poses.for_each([&](PoseObserver& observer) { observer.on_pose(estimate); });
}

void FrameLoop::finish() {
  if (held_pose_) send_pose(*held_pose_);
  held_pose_.reset();
  stats_.outputs_failed = outputs_failed();
}

std::uint64_t FrameLoop::outputs_failed() const {
  return io_.frames.failed() + io_.attempts.failed() + io_.poses.failed();
}

void FrameLoop::add_stage_times(const StageClock::Times& times) {
  for (const StageTime& stage : times) {
    StageTime* total = std::find_if(stats_.stage_totals.begin(), stats_.stage_totals.end(),
                                    [&](const StageTime& t) { return std::string_view(t.name) == stage.name; });
    if (total == stats_.stage_totals.end()) stats_.stage_totals.push_back(stage);
    else total->milliseconds += stage.milliseconds;
  }
}

}  // namespace irloc::firmware
