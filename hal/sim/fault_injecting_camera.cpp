#include "hal/sim/fault_injecting_camera.hpp"

#include <algorithm>
#include <string>
#include <thread>
#include <utility>
#include <variant>

#include "hal/device_lost.hpp"
#include "io/input_error.hpp"

namespace irloc::hal {

FaultInjectingCamera::FaultInjectingCamera(std::unique_ptr<Camera> camera, std::vector<Fault> faults,
                                           const std::atomic<bool>* stop, bool reopen_wrapped)
    : camera_(std::move(camera)), inner_strobe_(camera_->built_in_strobe()), stop_(stop), reopen_wrapped_(reopen_wrapped),
      faults_(std::move(faults)),
      fired_(faults_.size(), false) {
  // 16-bit slots hold either depth; sized once, here.
  for (auto& slot : slots_) slot.resize(static_cast<std::size_t>(width()) * static_cast<std::size_t>(height()));
}

bool FaultInjectingCamera::active(FaultKind kind, std::uint64_t seq) const {
  return std::any_of(faults_.begin(), faults_.end(), [&](const Fault& fault) {
    return fault.kind == kind && seq >= fault.at_seq && seq - fault.at_seq < static_cast<std::uint64_t>(fault.amount);
  });
}

void FaultInjectingCamera::set_led(bool on) {
  if (active(FaultKind::dark, last_seq_ + 1)) on = false;
  else if (active(FaultKind::desync, last_seq_ + 1)) on = !on;
  inner_strobe_->set_led(on);
}

// The LEDs did not light: the LED-on frame looks like the LED-off frame just before it.
void FaultInjectingCamera::show_last_off_frame(Frame& frame) {
  std::vector<std::uint16_t>& slot = slots_[next_slot_];
  next_slot_ = (next_slot_ + 1) % slots_.size();
  std::visit(
      [&](const auto& view) {
        using Pixel = std::remove_const_t<std::remove_pointer_t<decltype(view.data())>>;
        Pixel* out = reinterpret_cast<Pixel*>(slot.data());
        for (int y = 0; y < view.height(); ++y) std::copy_n(view.row(y), view.width(), out + y * view.width());
        frame.image = ImageView<const Pixel>(out, view.width(), view.height());
      },
      last_frame_.image);
}

namespace {

std::string jump_item(const Fault& fault) {
  return "jump@" + std::to_string(fault.at_seq) + (fault.amount < 0 ? "" : "+") + std::to_string(fault.amount);
}

}  // namespace

// The frames' clock only grows, so the first frame's time is the least any jump acts on.
void FaultInjectingCamera::check_clock_jumps(const Frame& first) const {
  std::vector<const Fault*> jumps;
  for (const Fault& fault : faults_) {
    if (fault.kind == FaultKind::jump) jumps.push_back(&fault);
  }
  std::stable_sort(jumps.begin(), jumps.end(), [](const Fault* a, const Fault* b) { return a->at_seq < b->at_seq; });
  std::int64_t jumped_ns = 0;
  for (const Fault* jump : jumps) {
    jumped_ns += jump->amount * 1'000'000'000;
    if (first.t_ns + jumped_ns < 0) {
      throw io::InputError("--inject-faults " + jump_item(*jump) + ": takes the frame clock below 0 (the camera's first frame is at " +
                       std::to_string(first.t_ns / 1'000'000) + " ms; a monotonic clock counts from its start)");
    }
  }
}

bool FaultInjectingCamera::next(Frame& frame) {
  if (lost_) throw DeviceLost("camera (injected fault): disconnected");
  while (true) {
    if (!camera_->next(frame)) return false;
    if (first_frame_) check_clock_jumps(frame);
    first_frame_ = false;
    std::int64_t jump_ns = 0;
    for (std::size_t k = 0; k < faults_.size(); ++k) {
      const Fault& fault = faults_[k];
      if (frame.seq < fault.at_seq) continue;
      if (fault.kind == FaultKind::jump) jump_ns += fault.amount * 1'000'000'000;
      if (fired_[k] || (fault.kind != FaultKind::lost && fault.kind != FaultKind::late)) continue;
      fired_[k] = true;
      if (fault.kind == FaultKind::late) {
        // In slices, so that a stop request is seen within 50 ms.
        const Clock::time_point due = Clock::now() + std::chrono::milliseconds(fault.amount);
        while (Clock::now() < due && !(stop_ && stop_->load())) {
          std::this_thread::sleep_for(std::min<Clock::duration>(due - Clock::now(), std::chrono::milliseconds(50)));
        }
      } else {
        lost_ = true;
        back_at_ = Clock::now() + std::chrono::milliseconds(fault.amount);
        skip_until_t_ns_ = frame.t_ns + fault.amount * 1'000'000;
        throw DeviceLost("camera (injected fault): disconnected before frame " + std::to_string(frame.seq));
      }
    }
    if (frame.t_ns < skip_until_t_ns_ || active(FaultKind::drop, frame.seq)) continue;
    if (__builtin_add_overflow(frame.t_ns, jump_ns, &frame.t_ns)) {
      throw io::InputError("--inject-faults: the clock jumps take frame " + std::to_string(frame.seq) + " past the largest time");
    }
    const bool recorded_on = frame.led_on;
    if (!inner_strobe_ && recorded_on && active(FaultKind::dark, frame.seq)) {
      if (!have_last_off_ || last_frame_.seq + 1 != frame.seq) continue;  // nothing to show instead
      show_last_off_frame(frame);
    }
    if (!inner_strobe_ && active(FaultKind::desync, frame.seq)) frame.led_on = !frame.led_on;
    have_last_off_ = !recorded_on;
    last_frame_ = frame;
    last_seq_ = frame.seq;
    return true;
  }
}

bool FaultInjectingCamera::reopen() {
  if (!lost_) return true;
  if (Clock::now() < back_at_) return false;
  if (reopen_wrapped_ && !camera_->reopen()) return false;
  lost_ = false;
  have_last_off_ = false;
  return true;
}

}  // namespace irloc::hal
