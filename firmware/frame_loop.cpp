#include "firmware/frame_loop.hpp"

#include <algorithm>
#include <string_view>

namespace irloc::firmware {

FrameLoop::FrameLoop(hal::Camera& camera, Localizer& localizer, const FrameLoopIo& io, std::optional<StrobeSync> strobe_sync)
    : camera_(camera), localizer_(localizer), io_(io), strobe_sync_(io.strobe ? strobe_sync : std::nullopt) {}

bool FrameLoop::step() {
  if (!camera_.next(frame_)) {
    if (const std::optional<StrobePair> pair = pairer_.flush()) attempt(*pair);
    return false;
  }
  ++stats_.frames;
  if (last_seq_ && frame_.seq > *last_seq_ + 1) stats_.dropped_frames += frame_.seq - *last_seq_ - 1;
  last_seq_ = frame_.seq;
  if (io_.strobe) io_.strobe->set_led(strobe_sync_->label(frame_));
  if (io_.recorder) io_.recorder->write(frame_);
  if (const std::optional<StrobePair> pair = pairer_.push(frame_)) attempt(*pair);
  return true;
}

void FrameLoop::attempt(const StrobePair& pair) {
  ++stats_.pose_attempts;
  if (!pair.off) ++stats_.unpaired;
  std::optional<StrobeVerdict> verdict;
  if (strobe_sync_ && pair.off) verdict = strobe_sync_->verify(pair);
  const bool compute = !verdict || *verdict == StrobeVerdict::verified;

  PoseEstimate estimate;
  if (compute) {
    estimate = localizer_.process(pair);
    add_stage_times(localizer_.last_stage_times());
  } else {
    ++stats_.strobe_rejected;
    estimate.seq = pair.on.seq;
    estimate.t_ns = pair.on.t_ns;
  }
  if (estimate.ok) ++stats_.poses_ok;
  if (io_.pose_csv) io_.pose_csv->write(estimate);
  if (io_.serial && io_.encoder) {
    const std::span<const std::uint8_t> bytes = io_.encoder->encode(estimate);
    if (!bytes.empty()) io_.serial->write_message(bytes);
  }
  if (io_.observer) io_.observer->on_attempt(pair, verdict, compute, estimate);
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
