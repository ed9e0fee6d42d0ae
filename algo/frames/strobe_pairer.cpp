#include "algo/frames/strobe_pairer.hpp"

namespace irloc {
namespace {

bool follows(const Frame& earlier, const Frame& later) { return later.seq == earlier.seq + 1; }

}  // namespace

std::optional<StrobePair> StrobePairer::push(const Frame& frame) {
  std::optional<StrobePair> result;
  if (waiting_on_) {
    if (!frame.led_on && follows(*waiting_on_, frame)) {
      result = StrobePair{*waiting_on_, frame};
    } else {
      result = StrobePair{*waiting_on_, std::nullopt};
    }
    waiting_on_.reset();
  }
  if (frame.led_on) {
    if (previous_ && !previous_->led_on && follows(*previous_, frame)) {
      result = StrobePair{frame, *previous_};
    } else {
      waiting_on_ = frame;
    }
  }
  previous_ = frame;
  return result;
}

std::optional<StrobePair> StrobePairer::flush() {
  std::optional<StrobePair> result;
  if (waiting_on_) result = StrobePair{*waiting_on_, std::nullopt};
  waiting_on_.reset();
  previous_.reset();
  return result;
}

}  // namespace irloc
