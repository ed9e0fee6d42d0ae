#include "hal/linux/libcamera_camera.hpp"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include <libcamera/camera.h>
#include <libcamera/camera_manager.h>
#include <libcamera/control_ids.h>
#include <libcamera/formats.h>
#include <libcamera/framebuffer.h>
#include <libcamera/framebuffer_allocator.h>
#include <libcamera/logging.h>
#include <libcamera/request.h>
#include <libcamera/stream.h>

#include "hal/device_lost.hpp"
#include "hal/linux/frame_timing.hpp"
#include "io/input_error.hpp"
#include "hal/linux/libcamera_compat.hpp"

namespace irloc::hal {

// One allocated frame buffer: its first plane mapped once, plus room for a converted image when
// the delivered format is not a grey image in place (YUYV, packed 10-bit).
struct LibcameraCamera::Buffer {
  libcamera::FrameBuffer* frame_buffer = nullptr;
  void* mapping = MAP_FAILED;
  std::size_t mapping_length = 0;
  const std::uint8_t* pixels = nullptr;  // first plane
  ConvertedImage converted;
};

namespace {

constexpr std::size_t index_of(CameraControl control) { return static_cast<std::size_t>(control); }

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

}  // namespace

LibcameraCamera::LibcameraCamera(const LibcameraSettings& settings, const std::atomic<bool>* stop)
    : settings_(settings), stop_(stop), manager_(std::make_unique<libcamera::CameraManager>()) {
  try {
    open();
  } catch (...) {
    shutdown();  // a half-opened camera must not call back into this object
    throw;
  }
}

void LibcameraCamera::open() {
  const LibcameraSettings& settings = settings_;
  const std::string what = settings.camera_id.empty() ? "camera" : "camera " + settings.camera_id;
  if (settings.buffer_count < 4) throw io::InputError(what + ": buffer_count must be at least 4");
  for (const std::string& format : settings.formats) {
    if (std::find(kDeliveredFormats.begin(), kDeliveredFormats.end(), format) == kDeliveredFormats.end()) {
      throw io::InputError(what + ": unknown pixel format '" + format + "' (known: " + join(kDeliveredFormats) + ")");
    }
  }
  // libcamera logs to stderr; irlocd's own error line says what went wrong. LIBCAMERA_LOG_LEVELS
  // still turns its log back on.
  if (!std::getenv("LIBCAMERA_LOG_LEVELS")) libcamera::logSetLevel("*", "ERROR");
  if (manager_->start() != 0) throw io::InputError(what + ": libcamera's camera manager did not start");

  const std::vector<std::shared_ptr<libcamera::Camera>> cameras = manager_->cameras();
  if (cameras.empty()) throw io::InputError(what + ": no camera found (libcamera lists none; is it connected and enabled?)");
  if (settings.camera_id.empty()) {
    camera_ = cameras.front();
  } else {
    camera_ = manager_->get(settings.camera_id);
    if (!camera_) {
      std::vector<std::string> ids;
      for (const auto& camera : cameras) ids.push_back(camera->id());
      throw io::InputError(what + ": not found; libcamera lists " + join(ids));
    }
  }
  id_ = camera_->id();
  if (camera_->acquire() != 0) {
    camera_.reset();
    throw io::InputError("camera " + id_ + ": in use by another process");
  }
  acquired_ = true;
  configure();
  map_buffers();

  // Only the controls this camera knows (a UVC webcam has no frame duration control, say).
  const libcamera::ControlInfoMap& known = camera_->controls();
  libcamera::ControlList controls(libcamera::controls::controls);
  set_manual_exposure(controls, known);
  if (known.count(&libcamera::controls::ExposureTime)) controls.set(libcamera::controls::ExposureTime, settings.exposure_us);
  if (known.count(&libcamera::controls::AnalogueGain)) controls.set(libcamera::controls::AnalogueGain, settings.analogue_gain);
  if (known.count(&libcamera::controls::FrameDurationLimits)) {
    const std::int64_t duration = settings.frame_duration_us;
    controls.set(libcamera::controls::FrameDurationLimits, {duration, duration});
  }
  read_control_ranges();

  camera_->requestCompleted.connect(this, &LibcameraCamera::on_request_completed);
  if (camera_->start(&controls) != 0) throw io::InputError("camera " + id_ + ": cannot start streaming");
  started_ = true;
  // The first request carries them too: libcamera's uvcvideo handler ignores the start controls
  // before 0.5.2: a UVC webcam would keep its own exposure and gain (make test-vm's UVC camera).
  for (const auto& [id, value] : controls) requests_.front()->controls().set(id, value);
  for (const auto& request : requests_) {
    if (!queue(*request)) throw io::InputError("camera " + id_ + ": cannot queue a request");
  }
}

void LibcameraCamera::configure() {
  const std::string what = "camera " + id_;
  const libcamera::Size wanted(static_cast<unsigned int>(settings_.width), static_cast<unsigned int>(settings_.height));
  std::vector<std::string> offered;
  // The ISP's viewfinder role gives processed mono/YUV; the raw role gives the sensor's own format.
  for (const libcamera::StreamRole role : {libcamera::StreamRole::Viewfinder, libcamera::StreamRole::Raw}) {
    for (const std::string& format : settings_.formats) {
      // A format this libcamera version does not know (R16 before 0.1) cannot be offered.
      if (!libcamera::PixelFormat::fromString(format).isValid()) continue;
      std::unique_ptr<libcamera::CameraConfiguration> config =
          camera_->generateConfiguration(std::vector<libcamera::StreamRole>{role});
      if (!config || config->size() != 1) continue;
      libcamera::StreamConfiguration& stream = config->at(0);
      stream.pixelFormat = libcamera::PixelFormat::fromString(format);
      stream.size = wanted;
      stream.bufferCount = settings_.buffer_count;
      const libcamera::CameraConfiguration::Status status = config->validate();
      if (status == libcamera::CameraConfiguration::Invalid) continue;
      offered.push_back(stream.pixelFormat.toString() + " " + stream.size.toString());
      if (stream.pixelFormat.toString() != format || stream.size != wanted) continue;
      if (stream.bufferCount < 4) continue;
      if (camera_->configure(config.get()) != 0) throw io::InputError(what + ": configuring " + format + " failed");
      stream_ = stream.stream();
      stride_ = stream.stride;
      pixel_format_ = format;
      pixel_layout_ = pixel_layout_of(format);
      return;
    }
  }
  throw io::InputError(what + ": cannot deliver " + wanted.toString() + " in " + join(settings_.formats) +
                   (offered.empty() ? "" : " (it offers " + join(offered) + ")"));
}

void LibcameraCamera::map_buffers() {
  const std::string what = "camera " + id_;
  allocator_ = std::make_unique<libcamera::FrameBufferAllocator>(camera_);
  if (allocator_->allocate(stream_) < 4) throw io::InputError(what + ": cannot allocate 4 frame buffers");
  const auto& frame_buffers = allocator_->buffers(stream_);
  buffers_.resize(frame_buffers.size());
  for (std::size_t i = 0; i < frame_buffers.size(); ++i) {
    Buffer& buffer = buffers_[i];
    buffer.frame_buffer = frame_buffers[i].get();
    // Every plane of one dmabuf is mapped together; the image is the first plane.
    const auto& planes = buffer.frame_buffer->planes();
    const libcamera::FrameBuffer::Plane& first = planes[0];
    std::size_t length = 0;
    for (const auto& plane : planes) {
      if (plane.fd.get() == first.fd.get()) length = std::max<std::size_t>(length, plane.offset + plane.length);
    }
    buffer.mapping = ::mmap(nullptr, length, PROT_READ, MAP_SHARED, first.fd.get(), 0);
    if (buffer.mapping == MAP_FAILED) throw io::InputError(what + ": cannot map a frame buffer");
    buffer.mapping_length = length;
    buffer.pixels = static_cast<const std::uint8_t*>(buffer.mapping) + first.offset;
    buffer.converted = converted_image_for(pixel_layout_, settings_.width, settings_.height);

    std::unique_ptr<libcamera::Request> request = camera_->createRequest(i);
    if (!request || request->addBuffer(stream_, buffer.frame_buffer) != 0) {
      throw io::InputError(what + ": cannot create a capture request");
    }
    requests_.push_back(std::move(request));
  }
  completed_.assign(requests_.size(), nullptr);
  held_.reserve(3);
}

LibcameraCamera::~LibcameraCamera() { shutdown(); }

void LibcameraCamera::shutdown() noexcept {
  if (camera_) {
    if (started_) camera_->stop();
    started_ = false;
    camera_->requestCompleted.disconnect(this);
    requests_.clear();
    for (Buffer& buffer : buffers_) {
      if (buffer.mapping != MAP_FAILED) ::munmap(buffer.mapping, buffer.mapping_length);
      buffer.mapping = MAP_FAILED;
    }
    allocator_.reset();
    if (acquired_) camera_->release();
    acquired_ = false;
    camera_.reset();
  }
  if (manager_) manager_->stop();
  manager_.reset();
}

// Runs on libcamera's thread: hand the request to next() without allocating.
void LibcameraCamera::on_request_completed(libcamera::Request* request) {
  {
    std::lock_guard lock(mutex_);
    completed_[(completed_head_ + completed_count_) % completed_.size()] = request;
    ++completed_count_;
  }
  completed_signal_.notify_one();
}

void LibcameraCamera::requeue(libcamera::Request* request) {
  request->reuse(libcamera::Request::ReuseBuffers);
  put_requested_controls(*request);
  if (!queue(*request)) throw DeviceLost("camera " + id_ + ": cannot requeue a request");
}

bool LibcameraCamera::queue(libcamera::Request& request) {
  mark_metadata_unfilled(*buffers_[request.cookie()].frame_buffer);
  return camera_->queueRequest(&request) == 0;
}

// A fresh camera manager sees the cameras as they are now (a replugged one included).
bool LibcameraCamera::reopen() {
  shutdown();
  buffers_.clear();
  held_.clear();
  completed_head_ = 0;
  completed_count_ = 0;
  last_sequence_.reset();
  try {
    manager_ = std::make_unique<libcamera::CameraManager>();
    open();
    return true;
  } catch (const io::InputError&) {
    shutdown();
    return false;
  }
}

// The oldest completed request, waiting until `deadline`; null once `stop` is set.
libcamera::Request* LibcameraCamera::wait_for_completed(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  while (completed_count_ == 0) {
    if (stop_ && stop_->load()) return nullptr;
    if (std::chrono::steady_clock::now() >= deadline) {
      throw DeviceLost("camera " + id_ + ": no frame for " + std::to_string(settings_.frame_timeout.count()) + " ms");
    }
    completed_signal_.wait_for(lock, std::chrono::milliseconds(50));
  }
  libcamera::Request* request = completed_[completed_head_];
  completed_head_ = (completed_head_ + 1) % completed_.size();
  --completed_count_;
  return request;
}

bool LibcameraCamera::next(Frame& frame) {
  // One deadline for the call: a camera that only completes broken frames has failed too.
  const auto deadline = std::chrono::steady_clock::now() + settings_.frame_timeout;
  libcamera::Request* request = nullptr;
  CompletedFrame completed;
  while (!request) {
    request = wait_for_completed(deadline);
    if (!request) return false;
    // A cancelled request or a frame the sensor flagged as broken is not handed out: its
    // sequence number is skipped, so the pipeline sees it as dropped.
    completed = completed_frame(*request, *buffers_[request->cookie()].frame_buffer);
    if (!completed.delivered) {
      requeue(request);
      request = nullptr;
    }
  }

  Buffer& buffer = buffers_[request->cookie()];
  if (last_sequence_ && completed.sequence > *last_sequence_ + 1) dropped_frames_ += completed.sequence - *last_sequence_ - 1;
  last_sequence_ = completed.sequence;

  frame.seq = completed.sequence;
  // The middle of row 0's exposure, from the sensor's frame start (frame_timing.hpp).
  const libcamera::ControlList& reported = request->metadata();
  const std::int64_t exposure_us = reported.get(libcamera::controls::ExposureTime).value_or(settings_.exposure_us);
  frame.t_ns = frame_time_ns(completed.frame_start_ns, exposure_us);
  current_[index_of(CameraControl::exposure_us)] = static_cast<double>(exposure_us);
  if (const auto gain = reported.get(libcamera::controls::AnalogueGain)) current_[index_of(CameraControl::analogue_gain)] = *gain;
  if (const auto duration = reported.get(libcamera::controls::FrameDuration)) {
    current_[index_of(CameraControl::frame_duration_us)] = static_cast<double>(*duration);
  }
  // Without a reported skew 0, and the configured line time holds.
  const std::int64_t skew_ns = reported.get(libcamera::controls::draft::SensorRollingShutterSkew).value_or(0);
  frame.line_time_ns = line_time_from_skew_ns(skew_ns, settings_.height);
  frame.led_on = false;  // the strobe schedule, not the camera, knows
  frame.image = grey_image(pixel_layout_, buffer.pixels, settings_.width, settings_.height, stride_,
                           buffer.converted);

  // The Camera contract keeps the last two frames valid: recycle the one before them.
  if (held_.size() == 3) {
    requeue(held_.front());
    held_.erase(held_.begin());
  }
  held_.push_back(request);
  return true;
}

bool LibcameraCamera::frames_are_16_bit() const {
  return pixel_layout_ == PixelLayout::mono16 || pixel_layout_ == PixelLayout::packed10;
}

// 10- and 12-bit raw formats arrive in 16-bit words with their own ceiling.
int LibcameraCamera::maxval() const {
  if (pixel_format_ == "R10" || pixel_format_ == "R10_CSI2P") return 1023;
  if (pixel_format_ == "R12") return 4095;
  return 65535;
}

CameraControls* LibcameraCamera::controls() {
  std::lock_guard lock(ranges_mutex_);
  return std::any_of(ranges_.begin(), ranges_.end(), [](const auto& range) { return range.has_value(); }) ? this : nullptr;
}

std::optional<ControlRange> LibcameraCamera::range(CameraControl control) const {
  std::lock_guard lock(ranges_mutex_);
  return ranges_[index_of(control)];
}

void LibcameraCamera::request(CameraControl control, double value) {
  requested_[index_of(control)] = value;
  requested_mask_.fetch_or(1u << index_of(control));
}

double LibcameraCamera::current(CameraControl control) const { return current_[index_of(control)]; }

void LibcameraCamera::read_control_ranges() {
  const libcamera::ControlInfoMap& known = camera_->controls();
  // A control of another type or shape than libcamera's own definition (a pipeline's quirk) is
  // left out rather than read as something it is not.
  const auto range_of = [&](const libcamera::ControlId& id, auto as_type) -> std::optional<ControlRange> {
    using Value = decltype(as_type);
    const auto found = known.find(&id);
    if (found == known.end()) return std::nullopt;
    const libcamera::ControlValue& min = found->second.min();
    const libcamera::ControlValue& max = found->second.max();
    constexpr libcamera::ControlType type = libcamera::details::control_type<Value>::value;
    if (min.isArray() || max.isArray() || min.type() != type || max.type() != type) return std::nullopt;
    return ControlRange{static_cast<double>(min.get<Value>()), static_cast<double>(max.get<Value>())};
  };
  std::lock_guard lock(ranges_mutex_);
  ranges_[index_of(CameraControl::exposure_us)] = range_of(libcamera::controls::ExposureTime, std::int32_t{});
  ranges_[index_of(CameraControl::analogue_gain)] = range_of(libcamera::controls::AnalogueGain, float{});
  ranges_[index_of(CameraControl::frame_duration_us)] = range_of(libcamera::controls::FrameDurationLimits, std::int64_t{});
  current_[index_of(CameraControl::exposure_us)] = settings_.exposure_us;
  current_[index_of(CameraControl::analogue_gain)] = settings_.analogue_gain;
  current_[index_of(CameraControl::frame_duration_us)] = static_cast<double>(settings_.frame_duration_us);
}

void LibcameraCamera::put_requested_controls(libcamera::Request& request) {
  const unsigned mask = requested_mask_.exchange(0);
  if (mask == 0) return;
  libcamera::ControlList& controls = request.controls();
  const auto requested = [&](CameraControl control) -> std::optional<double> {
    if ((mask & (1u << index_of(control))) == 0) return std::nullopt;
    return requested_[index_of(control)].load();
  };
  if (const std::optional<double> exposure = requested(CameraControl::exposure_us)) {
    settings_.exposure_us = static_cast<std::int32_t>(std::lround(*exposure));
    controls.set(libcamera::controls::ExposureTime, settings_.exposure_us);
  }
  if (const std::optional<double> gain = requested(CameraControl::analogue_gain)) {
    settings_.analogue_gain = static_cast<float>(*gain);
    controls.set(libcamera::controls::AnalogueGain, settings_.analogue_gain);
  }
  if (const std::optional<double> duration = requested(CameraControl::frame_duration_us)) {
    settings_.frame_duration_us = std::llround(*duration);
    const std::int64_t us = settings_.frame_duration_us;
    controls.set(libcamera::controls::FrameDurationLimits, {us, us});
  }
}

}  // namespace irloc::hal
