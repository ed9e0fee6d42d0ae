#pragma once
// irlocd --survey MAP_OUT (docs/survey.md): every pose attempt's dot-marker observations go to
// the survey estimator; moved, added and conflicting markers get one stderr line each (and are
// counted for --stats); the localizer gets the established markers' poses and sigmas after every
// attempt, and MAP_OUT is replaced atomically every `interval` of frame time and at the end. The
// map is estimated in the frame loop (bounded by the graph's capacity) and written to the file on
// a thread of its own (background_map_writer.hpp): a slow disk never holds up a frame. A write
// that fails (the disk filled) leaves the previous map in place and is tried again at the next
// write: one line when writing fails, one when it works again.

#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include "algo/pipeline/localizer.hpp"
#include "algo/survey/survey_estimator.hpp"
#include "firmware/background_map_writer.hpp"
#include "firmware/frame_loop.hpp"

namespace irloc::firmware {

class SurveyWriter final : public AttemptObserver {
 public:
  static constexpr std::chrono::seconds kDefaultInterval{10};

  // Starts from the localizer's map (read from map_file). The localizer's dot source must report
  // every marker (DotSourceConfig::observe_every_marker). Throws io::InputError when the map has
  // no fixed dot marker (nothing would define the world frame) or the robot is not level (dof 6).
  SurveyWriter(const std::filesystem::path& output, const std::filesystem::path& map_file, Localizer& localizer, std::FILE* log,
               std::chrono::nanoseconds interval = kDefaultInterval);

  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed,
                  const PoseEstimate& estimate) override;
  // Writes the map as it stands (the end of the run) and waits until it is written.
  void finish();
  // Waits until every map handed to the file's thread is written (or has failed).
  void wait_until_written() { file_.wait_until_written(); }
  // Whether the last write of the map that ended failed (the file then holds an older map).
  bool last_write_failed() { return file_.last_write_failed(); }
  // Events reported so far, by kind.
  std::uint64_t reported(survey::SurveyEvent::Kind kind) const { return counts_[static_cast<std::size_t>(kind)]; }

 private:
  void report_events();
  void publish();
  void use_established_markers();

  Localizer& localizer_;
  std::FILE* log_;
  std::chrono::nanoseconds interval_;
  survey::SurveyEstimator survey_;
  std::optional<std::int64_t> last_write_ns_;
  std::vector<DotMarker> established_;  // reused every attempt: room for the graph's capacity
  std::array<std::uint64_t, 3> counts_{};  // by SurveyEvent::Kind
  BackgroundMapWriter file_;
};

}  // namespace irloc::firmware
