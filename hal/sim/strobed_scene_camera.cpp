#include "hal/sim/strobed_scene_camera.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>
#include <utility>

namespace irloc::hal {

namespace {

std::size_t index_of(CameraControl control) { return static_cast<std::size_t>(control); }

}  // namespace

StrobedSceneCamera::StrobedSceneCamera(StrobedSceneSettings settings) : settings_(std::move(settings)) {
  for (auto& slot : slots_) slot.resize(static_cast<std::size_t>(settings_.width) * static_cast<std::size_t>(settings_.height));
  const double values[] = {settings_.exposure_us, settings_.analogue_gain,
                           std::chrono::duration<double, std::micro>(settings_.frame_period).count()};
  for (std::size_t i = 0; i < kCameraControls.size(); ++i) {
    requested_[i].store(values[i]);
    current_[i].store(values[i]);
  }
}

std::optional<ControlRange> StrobedSceneCamera::range(CameraControl control) const {
  switch (control) {
    case CameraControl::exposure_us: return ControlRange{50, 20000};
    case CameraControl::analogue_gain: return ControlRange{1, 16};
    case CameraControl::frame_duration_us: return ControlRange{0, 1000000};  // 0: unpaced
  }
  return std::nullopt;
}

void StrobedSceneCamera::request(CameraControl control, double value) { requested_[index_of(control)].store(value); }

double StrobedSceneCamera::current(CameraControl control) const { return current_[index_of(control)].load(); }

void StrobedSceneCamera::apply_requested_controls() {
  for (std::size_t i = 0; i < kCameraControls.size(); ++i) current_[i].store(requested_[i].load());
  settings_.frame_period = std::chrono::nanoseconds(
      static_cast<std::int64_t>(current_[index_of(CameraControl::frame_duration_us)].load() * 1000));
}

void StrobedSceneCamera::set_led(bool on) {
  if (!last_delivered_) return;  // before the first frame the LEDs stay off
  Command& command = commands_[*last_delivered_ % kHistory];
  command.after_seq = *last_delivered_;
  command.on = on;
}

bool StrobedSceneCamera::led_for_exposure_of(std::uint64_t seq) const {
  // The latest command issued after a frame at least pipeline_depth frames earlier.
  const unsigned int depth = seq >= settings_.depth_change_at_seq ? settings_.pipeline_depth_after_change : settings_.pipeline_depth;
  if (seq < depth) return false;
  const std::uint64_t newest = seq - depth;
  for (std::uint64_t back = 0; back < kHistory && back <= newest; ++back) {
    const Command& command = commands_[(newest - back) % kHistory];
    if (command.after_seq == newest - back) return command.on;
  }
  return false;
}

bool StrobedSceneCamera::truly_lit(std::uint64_t seq) const {
  const std::size_t index = seq % kHistory;
  return lit_seq_[index] == seq && lit_[index].value_or(false);
}

void StrobedSceneCamera::render(std::uint64_t seq, bool lit, std::vector<std::uint8_t>& pixels) const {
  const int width = settings_.width;
  const int height = settings_.height;
  // Light collected: the settings' grey levels are those of their exposure at gain 1.
  const double brightness = current(CameraControl::exposure_us) / settings_.exposure_us *
                            current(CameraControl::analogue_gain) / settings_.analogue_gain;
  const auto scaled = [&](std::uint8_t level) { return static_cast<int>(std::lround(level * brightness)); };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Deterministic sensor noise of +-3 grey levels, different in every frame.
      const std::uint64_t hash = (static_cast<std::uint64_t>(x) * 73856093u) ^ (static_cast<std::uint64_t>(y) * 19349663u) ^
                                 (seq * 83492791u);
      int value = scaled(settings_.background) + static_cast<int>(hash % 7) - 3;
      const bool in_lamp = x >= width / 8 && x < width / 8 + 6 && y >= height / 8 && y < height / 8 + 6;
      const bool in_reflector = (x % 16 == 10 && y % 12 == 8) || (x % 16 == 11 && y % 12 == 8) ||
                                (x % 16 == 10 && y % 12 == 9) || (x % 16 == 11 && y % 12 == 9);
      if (in_lamp) value = scaled(settings_.lamp);
      if (in_reflector && lit) value = scaled(settings_.reflector);
      pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)] =
          static_cast<std::uint8_t>(std::clamp(value, 0, 255));
    }
  }
}

bool StrobedSceneCamera::next(Frame& frame) {
  while (next_seq_ < settings_.frames) {
    if (next_seq_ >= settings_.stall_at_seq) {
      while (!settings_.stop || !settings_.stop->load()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
      return false;
    }
    const std::uint64_t seq = next_seq_++;
    const bool lit = led_for_exposure_of(seq);
    lit_[seq % kHistory] = lit;
    lit_seq_[seq % kHistory] = seq;
    if (std::find(settings_.dropped_seqs.begin(), settings_.dropped_seqs.end(), seq) != settings_.dropped_seqs.end()) continue;

    apply_requested_controls();
    if (settings_.frame_period.count() > 0) {
      const auto now = std::chrono::steady_clock::now();
      next_frame_time_ = next_frame_time_ == std::chrono::steady_clock::time_point{} ? now : next_frame_time_ + settings_.frame_period;
      std::this_thread::sleep_until(next_frame_time_);
    }
    std::vector<std::uint8_t>& pixels = slots_[next_slot_];
    next_slot_ = (next_slot_ + 1) % slots_.size();
    render(seq, lit, pixels);
    frame.seq = seq;
    // Stamped on CLOCK_MONOTONIC (libcamera's SensorTimestamp clock) once the image is complete:
    // a delivered frame, without a sensor's exposure and readout before it.
    frame.t_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
    frame.led_on = false;
    frame.image = ImageView8(pixels.data(), settings_.width, settings_.height, settings_.width);
    last_delivered_ = seq;
    return true;
  }
  return false;
}

}  // namespace irloc::hal
