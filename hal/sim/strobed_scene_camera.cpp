#include "hal/sim/strobed_scene_camera.hpp"

#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>

namespace irloc::hal {

StrobedSceneCamera::StrobedSceneCamera(StrobedSceneSettings settings) : settings_(std::move(settings)) {
  for (auto& slot : slots_) slot.resize(static_cast<std::size_t>(settings_.width) * static_cast<std::size_t>(settings_.height));
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
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Deterministic sensor noise of +-3 grey levels, different in every frame.
      const std::uint64_t hash = (static_cast<std::uint64_t>(x) * 73856093u) ^ (static_cast<std::uint64_t>(y) * 19349663u) ^
                                 (seq * 83492791u);
      int value = settings_.background + static_cast<int>(hash % 7) - 3;
      const bool in_lamp = x >= width / 8 && x < width / 8 + 6 && y >= height / 8 && y < height / 8 + 6;
      const bool in_reflector = (x % 16 == 10 && y % 12 == 8) || (x % 16 == 11 && y % 12 == 8) ||
                                (x % 16 == 10 && y % 12 == 9) || (x % 16 == 11 && y % 12 == 9);
      if (in_lamp) value = settings_.lamp;
      if (in_reflector && lit) value = settings_.reflector;
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
