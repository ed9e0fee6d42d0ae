#pragma once
// The camera interface: where frames come from (a sensor, a recorded dataset, the simulator).

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

#include "algo/frames/frame.hpp"

namespace irloc::hal {

class CameraControls;
class Strobe;

class Camera {
 public:
  virtual ~Camera() = default;

  virtual int width() const = 0;
  virtual int height() const = 0;

  // Fills `frame` with the next frame in capture order; false when the stream has ended.
  // The pixels stay valid until two more frames have been taken (see StrobePairer).
  // Allocates nothing. Bad input throws io::InputError naming the source and the problem; a device
  // that stops delivering (unplugged, hung past its frame timeout) throws DeviceLost.
  virtual bool next(Frame& frame) = 0;

  // After DeviceLost: one attempt to bring the device back, not blocking for long. True when
  // next() delivers again (its sequence numbers may start over). A camera that cannot come back
  // (a recorded dataset) returns false forever.
  virtual bool reopen() { return false; }

  // The files it reads frames from (none for a device), which no output may overwrite.
  virtual std::vector<std::filesystem::path> input_files() const { return {}; }

  // The largest value a pixel of its frames can take (recorded PGMs carry it as maxval).
  virtual int maxval() const { return 65535; }

  // Its frames are 16-bit (GrayImageView's 16-bit kind), known before the first next().
  virtual bool frames_are_16_bit() const { return false; }

  // The LED switch the camera drives itself (the simulator lights its own scene); null for a
  // camera whose LEDs are wired to a GPIO line.
  virtual Strobe* built_in_strobe() { return nullptr; }

  // Its setup controls (hal/camera_controls.hpp); null for a camera without any (a recording).
  virtual CameraControls* controls() { return nullptr; }

  // CLOCK_MONOTONIC's reading minus its frames' t_ns at the same instant, where its frames' capture
  // is known on CLOCK_MONOTONIC (the clock of the serial writes: capture-to-write latency): 0 for
  // a camera that stamps on it (libcamera's SensorTimestamp, the simulator); a recording replayed
  // at its pace knows it once it started; empty for a recording replayed as fast as it can.
  virtual std::optional<std::int64_t> monotonic_minus_frame_clock_ns() const { return std::nullopt; }
};

}  // namespace irloc::hal
