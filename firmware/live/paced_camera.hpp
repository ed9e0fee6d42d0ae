#pragma once
// A recording replayed at the pace it was recorded (its frames' t_ns), as a camera delivers it: for
// a person watching it in the live view, and (--paced) for measuring the capture-to-write latency
// of a recorded drive. Otherwise a replay runs as fast as it can.

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>

#include "hal/camera.hpp"

namespace irloc::firmware {

class PacedCamera final : public hal::Camera {
 public:
  // `stop` (may be null) ends a wait early.
  PacedCamera(std::unique_ptr<hal::Camera> camera, const std::atomic<bool>* stop) : camera_(std::move(camera)), stop_(stop) {}

  int width() const override { return camera_->width(); }
  int height() const override { return camera_->height(); }
  bool next(Frame& frame) override;
  bool reopen() override { return camera_->reopen(); }
  std::vector<std::filesystem::path> input_files() const override { return camera_->input_files(); }
  int maxval() const override { return camera_->maxval(); }
  bool frames_are_16_bit() const override { return camera_->frames_are_16_bit(); }
  hal::Strobe* built_in_strobe() override { return camera_->built_in_strobe(); }
  hal::CameraControls* controls() override { return camera_->controls(); }
  // Each frame is due at its t_ns shifted onto steady_clock (CLOCK_MONOTONIC) by the first frame's.
  std::optional<std::int64_t> monotonic_minus_frame_clock_ns() const override;

 private:
  using Clock = std::chrono::steady_clock;
  std::unique_ptr<hal::Camera> camera_;
  const std::atomic<bool>* stop_;
  std::optional<std::int64_t> first_t_ns_;
  Clock::time_point started_{};
};

}  // namespace irloc::firmware
