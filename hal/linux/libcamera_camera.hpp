#pragma once
// A camera driven through libcamera (Raspberry Pi CSI sensors, UVC webcams): manual exposure and
// gain, a fixed frame duration, a mono or raw format where the sensor offers one. Builds against
// libcamera 0.0.3 (Debian 12) to 0.5; the API differences are in libcamera_compat.hpp.
//
// Buffers are allocated and mapped once at start-up; requests are recycled, never allocated,
// while running. Each frame carries libcamera's sequence number (a gap is a dropped frame,
// counted in dropped_frames()), its time t_ns (the middle of the top row's exposure, from the
// SensorTimestamp, CLOCK_MONOTONIC) and its rolling shutter's line time (libcamera's reported
// skew, else the board's).
//
// Setup controls (CameraControls, for the live view): exposure, analogue gain and frame duration,
// each where the camera has it, within the range it reports; a request is put on the next request
// requeued (libcamera then applies it a few frames later, as the sensor's pipeline allows), and
// current() is what the frames' metadata report. A change allocates once inside libcamera's
// ControlList; an unchanged frame allocates nothing.

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "hal/camera.hpp"
#include "hal/camera_controls.hpp"
#include "hal/linux/delivered_image.hpp"

namespace libcamera {
class Camera;
class CameraManager;
class FrameBufferAllocator;
class Request;
class Stream;
}  // namespace libcamera

namespace irloc::hal {

struct LibcameraSettings {
  std::string camera_id;             // libcamera's ID, or empty for the first camera
  int width = 0;                     // the calibration's image size
  int height = 0;
  // Pixel formats to try, best first: R8, R10, R12, R16 (mono, 16-bit containers), R10_CSI2P
  // (packed mono, unpacked here), YUV420, NV12 (the Y plane is the image), YUYV (Y copied out).
  std::vector<std::string> formats = kDeliveredFormats;
  std::int64_t frame_duration_us = 16667;  // fixed: min = max frame duration
  std::int32_t exposure_us = 2000;         // manual exposure (auto exposure off)
  float analogue_gain = 1.0f;              // manual gain
  unsigned int buffer_count = 6;           // >= 4: three frames are held by the pipeline
  std::chrono::milliseconds frame_timeout{2000};  // no frame this long: the camera has failed
};

class LibcameraCamera final : public Camera, public CameraControls {
 public:
  // Opens, configures and starts the camera. `stop` (may be null) is polled while waiting for a
  // frame, so a signal handler can end next(). Throws io::InputError "camera ID: problem" when there
  // is no camera, it is busy, or it cannot deliver the size in any of the formats.
  LibcameraCamera(const LibcameraSettings& settings, const std::atomic<bool>* stop);
  ~LibcameraCamera() override;
  LibcameraCamera(const LibcameraCamera&) = delete;
  LibcameraCamera& operator=(const LibcameraCamera&) = delete;

  int width() const override { return settings_.width; }
  int height() const override { return settings_.height; }
  // Waits for the next completed frame; false once `stop` is set. Throws DeviceLost when no
  // frame arrives within frame_timeout. Allocates nothing.
  bool next(Frame& frame) override;
  std::optional<std::int64_t> monotonic_minus_frame_clock_ns() const override { return 0; }
  // Null when the camera has none of the three controls (its settings are then the board's, fixed).
  CameraControls* controls() override;
  std::optional<ControlRange> range(CameraControl control) const override;
  void request(CameraControl control, double value) override;
  double current(CameraControl control) const override;
  // Closes everything and opens the camera again from a new camera manager (start-up work:
  // it allocates). False, with the camera closed, while it is not back.
  bool reopen() override;

  std::uint64_t dropped_frames() const { return dropped_frames_; }
  const std::string& id() const { return id_; }
  const std::string& pixel_format() const { return pixel_format_; }
  int maxval() const override;
  bool frames_are_16_bit() const override;

 private:
  struct Buffer;

  void open();
  void shutdown() noexcept;
  void configure();
  void map_buffers();
  void on_request_completed(libcamera::Request* request);
  void requeue(libcamera::Request* request);
  // Marks the request's buffer unfilled (libcamera_compat.hpp) and queues it; false if refused.
  bool queue(libcamera::Request& request);
  libcamera::Request* wait_for_completed(std::chrono::steady_clock::time_point deadline);
  void read_control_ranges();
  // The requested controls not yet put on a request, onto this one (and into settings_, so that a
  // reopened camera starts with them).
  void put_requested_controls(libcamera::Request& request);

  LibcameraSettings settings_;
  const std::atomic<bool>* stop_;
  std::string id_;
  std::string pixel_format_;
  PixelLayout pixel_layout_ = PixelLayout::mono8;  // of pixel_format_, set with it
  std::unique_ptr<libcamera::CameraManager> manager_;
  std::shared_ptr<libcamera::Camera> camera_;
  std::unique_ptr<libcamera::FrameBufferAllocator> allocator_;
  libcamera::Stream* stream_ = nullptr;
  unsigned int stride_ = 0;  // bytes per row of the delivered format
  std::vector<std::unique_ptr<libcamera::Request>> requests_;
  std::vector<Buffer> buffers_;  // indexed by the request's cookie
  bool acquired_ = false;
  bool started_ = false;

  // Completed requests, handed from libcamera's thread to next(); capacity = requests_.size().
  std::mutex mutex_;
  std::condition_variable completed_signal_;
  std::vector<libcamera::Request*> completed_;
  std::size_t completed_head_ = 0;
  std::size_t completed_count_ = 0;

  // The frames handed out and still valid (Camera contract: until two more are taken).
  std::vector<libcamera::Request*> held_;
  std::optional<std::uint32_t> last_sequence_;
  // Setup controls, by CameraControl: the ranges read at open (under ranges_mutex_: reopen rereads
  // them while the live view's thread may read them), the values requested from any thread (a bit
  // of requested_mask_ per control), and the values the last frame's metadata reported.
  mutable std::mutex ranges_mutex_;
  std::array<std::optional<ControlRange>, kCameraControls.size()> ranges_{};
  std::array<std::atomic<double>, kCameraControls.size()> requested_{};
  std::atomic<unsigned> requested_mask_{0};
  std::array<std::atomic<double>, kCameraControls.size()> current_{};
  std::uint64_t dropped_frames_ = 0;
};

}  // namespace irloc::hal
