#pragma once
// irlocd --annotate DIR: every pose attempt of a run (a recorded or rendered dataset, or a live
// camera) as a JPEG with the live view's drawing (live_drawing.hpp), DIR/attempt_SEQ.jpg, SEQ the
// LED-on frame's sequence number: what each source found in the frame, and why not.
// Drawing and writing allocate: an offline tool, not for the robot's frame loop.

#include <filesystem>
#include <optional>

#include "firmware/live/jpeg_encoder.hpp"
#include "firmware/live/live_drawing.hpp"
#include "firmware/live/live_snapshot.hpp"
#include "io/files/output_file.hpp"

namespace irloc::firmware {

class AnnotatedFrames final : public AttemptObserver {
 public:
  // Creates DIR (refused when it holds anything, as --record is). Throws InputError.
  AnnotatedFrames(const std::filesystem::path& dir, const Localizer& localizer, int width, int height, int maxval,
                  LiveImage image);

  void watch(const FrameLoop& loop) { publisher_.watch(loop); }
  // Throws InputError when a file cannot be written.
  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                  const PoseEstimate& estimate) override;

  std::uint64_t written() const { return written_; }

 private:
  io::NewFilesFolder folder_;
  LiveSlot slot_;
  LivePublisher publisher_;
  LiveViewGeometry geometry_;
  LiveImage image_;
  LiveSnapshot snapshot_;
  BgrxImage picture_;
  JpegEncoder encoder_;
  std::uint64_t written_ = 0;
};

}  // namespace irloc::firmware
