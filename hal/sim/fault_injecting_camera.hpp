#pragma once
// A camera that passes another camera's frames through with faults injected (hal/sim/fault_plan):
// software-in-the-loop tests of how irlocd lives with a camera that disconnects, stalls or drops
// frames, LEDs that die or lose their sync, and a clock that jumps. The LED faults act on the
// wrapped camera's built-in strobe when it has one (the simulator), else on the frames' recorded
// labels (a dataset: a dark LED-on frame shows the LED-off frame before it).

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "hal/camera.hpp"
#include "hal/sim/fault_plan.hpp"
#include "hal/strobe.hpp"

namespace irloc::hal {

class FaultInjectingCamera final : public Camera, public Strobe {
 public:
  // `stop` (may be null) ends a late frame's wait early (irlocd's SIGTERM). With `reopen_wrapped`
  // (a libcamera camera) a `lost` fault's end closes and opens the wrapped camera as a real
  // disconnection does; without it (a recording, the simulator) its frames go on where they were.
  FaultInjectingCamera(std::unique_ptr<Camera> camera, std::vector<Fault> faults, const std::atomic<bool>* stop = nullptr,
                       bool reopen_wrapped = false);

  int width() const override { return camera_->width(); }
  int height() const override { return camera_->height(); }
  // Throws DeviceLost at a `lost` fault; io::InputError naming the plan at the first frame when its
  // clock jumps would take the frame clock below 0 (a monotonic clock counts from its start), or
  // at the frame they would take it past the largest time.
  bool next(Frame& frame) override;
  bool reopen() override;            // true once the `lost` fault's time is over (and the wrapped camera reopened)
  std::vector<std::filesystem::path> input_files() const override { return camera_->input_files(); }
  int maxval() const override { return camera_->maxval(); }
  bool frames_are_16_bit() const override { return camera_->frames_are_16_bit(); }
  Strobe* built_in_strobe() override { return inner_strobe_ ? this : nullptr; }
  CameraControls* controls() override { return camera_->controls(); }
  std::optional<std::int64_t> monotonic_minus_frame_clock_ns() const override { return camera_->monotonic_minus_frame_clock_ns(); }
  void set_led(bool on) override;

 private:
  using Clock = std::chrono::steady_clock;

  bool active(FaultKind kind, std::uint64_t seq) const;  // a frame-count fault covers seq
  void show_last_off_frame(Frame& frame);
  void check_clock_jumps(const Frame& first) const;

  std::unique_ptr<Camera> camera_;
  Strobe* inner_strobe_;
  const std::atomic<bool>* stop_;
  bool reopen_wrapped_;
  bool first_frame_ = true;
  std::vector<Fault> faults_;
  std::vector<bool> fired_;            // lost and late faults happen once
  bool lost_ = false;
  Clock::time_point back_at_{};        // a lost camera can be reopened from then on
  std::int64_t skip_until_t_ns_ = 0;   // frames exposed while it was lost are gone
  std::uint64_t last_seq_ = 0;         // the LED faults follow the last frame delivered
  bool have_last_off_ = false;
  Frame last_frame_;
  std::array<std::vector<std::uint16_t>, 3> slots_;  // dark frames' pixels, valid for two more frames
  std::size_t next_slot_ = 0;
};

}  // namespace irloc::hal
