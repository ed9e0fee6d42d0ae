#pragma once
// A simulated camera and LED strobe in one device, for software-in-the-loop runs of irlocd's
// strobe scheduling: frames of a dim scene with a ceiling lamp (bright in every frame) and a few
// retro-reflective spots that shine only in frames exposed while the LEDs were on.
//
// Setup controls (CameraControls): exposure and analogue gain scale every grey level of the scene
// (the noise stays); the frame duration paces it (0: unpaced, frames as fast as asked).
//
// Timing model: the sensor pipeline is `pipeline_depth` frames deep, so an LED command issued
// after frame s was delivered first lights frame s + pipeline_depth. A dropped frame is exposed
// (its sequence number is used) but never delivered.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <optional>
#include <vector>

#include "hal/camera.hpp"
#include "hal/camera_controls.hpp"
#include "hal/strobe.hpp"

namespace irloc::hal {

struct StrobedSceneSettings {
  int width = 64;
  int height = 48;
  std::uint64_t frames = 40;                 // sequence numbers 0 .. frames-1
  std::chrono::nanoseconds frame_period{0};  // paced like a sensor when > 0, else as fast as asked
  unsigned int pipeline_depth = 1;
  // From this frame on the pipeline is this deep instead (a sensor mode change, a stall): the
  // strobe falls out of sync.
  std::uint64_t depth_change_at_seq = UINT64_MAX;
  unsigned int pipeline_depth_after_change = 1;
  std::vector<std::uint64_t> dropped_seqs;   // exposed but not delivered
  // The sensor hangs before delivering this frame: next() waits until `stop` is set (a stalled
  // pipeline, for the service watchdog's tests), then ends the stream.
  std::uint64_t stall_at_seq = UINT64_MAX;
  const std::atomic<bool>* stop = nullptr;
  std::uint8_t background = 20;
  std::uint8_t lamp = 230;
  std::uint8_t reflector = 180;
  double exposure_us = 2000;     // the grey levels above are those of this exposure at gain 1
  double analogue_gain = 1;
};

class StrobedSceneCamera final : public Camera, public Strobe, public CameraControls {
 public:
  explicit StrobedSceneCamera(StrobedSceneSettings settings);

  int width() const override { return settings_.width; }
  int height() const override { return settings_.height; }
  bool next(Frame& frame) override;  // frame.led_on is left false: the schedule sets it
  void set_led(bool on) override;
  Strobe* built_in_strobe() override { return this; }
  CameraControls* controls() override { return this; }
  std::optional<std::int64_t> monotonic_minus_frame_clock_ns() const override { return 0; }
  std::optional<ControlRange> range(CameraControl control) const override;
  void request(CameraControl control, double value) override;
  double current(CameraControl control) const override;

  // Ground truth: whether the LEDs lit frame `seq` (known once it was rendered).
  bool truly_lit(std::uint64_t seq) const;

 private:
  static constexpr std::size_t kHistory = 64;
  struct Command {
    std::optional<std::uint64_t> after_seq;  // issued after this frame was delivered
    bool on = false;
  };

  bool led_for_exposure_of(std::uint64_t seq) const;
  void render(std::uint64_t seq, bool lit, std::vector<std::uint8_t>& pixels) const;
  void apply_requested_controls();

  StrobedSceneSettings settings_;
  std::uint64_t next_seq_ = 0;
  std::optional<std::uint64_t> last_delivered_;
  std::array<Command, kHistory> commands_{};          // by after_seq % kHistory
  std::array<std::optional<bool>, kHistory> lit_{};   // by seq % kHistory, rendered frames
  std::array<std::optional<std::uint64_t>, kHistory> lit_seq_{};
  std::array<std::vector<std::uint8_t>, 3> slots_;
  std::size_t next_slot_ = 0;
  std::chrono::steady_clock::time_point next_frame_time_{};
  // By CameraControl: what another thread asked for, and what the last frame was taken with.
  std::array<std::atomic<double>, kCameraControls.size()> requested_{};
  std::array<std::atomic<double>, kCameraControls.size()> current_{};
};

}  // namespace irloc::hal
