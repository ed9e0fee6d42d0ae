#pragma once
// The frame loop's outputs as its observers: the recording (--record), the pose CSV (--pose-csv)
// and the pose stream (serial or UDP). A write that fails (the disk filled) stops the recording or
// the pose CSV with one stderr line; localization and the pose stream go on.

#include <optional>

#include "firmware/frame_loop.hpp"
#include "firmware/latency_histogram.hpp"
#include "firmware/serial_link.hpp"
#include "hal/camera.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "io/files/pose_csv_writer.hpp"

namespace irloc::firmware {

class RecordingOutput final : public FrameObserver {
 public:
  explicit RecordingOutput(io::DatasetWriter& writer) : writer_(writer) {}
  void on_frame(const Frame& frame) override;
  bool failed() const override { return failed_; }

 private:
  io::DatasetWriter& writer_;
  bool failed_ = false;
};

class PoseCsvOutput final : public PoseObserver {
 public:
  explicit PoseCsvOutput(io::PoseCsvWriter& writer) : writer_(writer) {}
  void on_pose(const PoseEstimate& estimate) override;
  bool failed() const override { return failed_; }

 private:
  io::PoseCsvWriter& writer_;
  bool failed_ = false;
};

// Sends every attempt's pose, and measures capture to serial write per pose sent where the camera
// knows its frames' capture on the link's clock (hal::Camera::monotonic_minus_frame_clock_ns).
class PoseStreamOutput final : public PoseObserver {
 public:
  PoseStreamOutput(SerialLink& link, const hal::Camera& camera) : link_(link), camera_(camera) {}
  void on_pose(const PoseEstimate& estimate) override;
  const LatencyHistogram& latency() const { return latency_; }

 private:
  SerialLink& link_;
  const hal::Camera& camera_;
  LatencyHistogram latency_;
};

}  // namespace irloc::firmware
