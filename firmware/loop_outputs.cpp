#include "firmware/loop_outputs.hpp"

#include <cstdio>

#include "firmware/warning_log.hpp"
#include "io/input_error.hpp"

namespace irloc::firmware {

void RecordingOutput::on_frame(const Frame& frame) {
  if (failed_) return;
  try {
    writer_.write(frame);
  } catch (const io::InputError& e) {
    print_warning(stderr, "--record %s: %s: recording stopped at frame %llu; the dataset holds the %llu frames before it",
                  writer_.dir().c_str(), e.what(), static_cast<unsigned long long>(frame.seq),
                  static_cast<unsigned long long>(writer_.frames_written()));
    failed_ = true;
  }
}

void PoseCsvOutput::on_pose(const PoseEstimate& estimate) {
  if (failed_) return;
  try {
    writer_.write(estimate);
  } catch (const io::InputError& e) {
    print_warning(stderr, "--pose-csv %s: %s: pose rows stopped at frame %llu; the file holds the %llu whole rows before it",
                  writer_.path().c_str(), e.what(), static_cast<unsigned long long>(estimate.seq),
                  static_cast<unsigned long long>(writer_.rows_written()));
    failed_ = true;
  }
}

void PoseStreamOutput::on_pose(const PoseEstimate& estimate) {
  const std::optional<std::int64_t> written_ns = link_.send_attempt(estimate);
  const std::optional<std::int64_t> clock_offset_ns = camera_.monotonic_minus_frame_clock_ns();
  if (written_ns && clock_offset_ns) latency_.add(*written_ns - (estimate.t_ns + *clock_offset_ns));
}

}  // namespace irloc::firmware
