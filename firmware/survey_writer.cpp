#include "firmware/survey_writer.hpp"

#include <algorithm>

#include "io/input_error.hpp"

namespace irloc::firmware {
namespace {

const LocalizerSetup& checked_setup(const std::filesystem::path& output, const std::filesystem::path& map_file,
                                    const Localizer& localizer) {
  const LocalizerSetup& setup = localizer.setup();
  if (setup.dof == Dof::full6) {
    throw io::InputError("--survey " + output.string() + ": needs a level robot (robot dof 3 or 4)");
  }
  const auto& markers = setup.map.dot_markers;
  if (std::none_of(markers.begin(), markers.end(), [](const DotMarker& marker) { return marker.fixed; })) {
    throw io::InputError(map_file.string() + ": dot_markers: --survey needs one with `fixed: true` (it defines the world frame)");
  }
  return setup;
}

survey::SurveyEstimator make_estimator(const std::filesystem::path& output, const std::filesystem::path& map_file,
                                       const Localizer& localizer) {
  const LocalizerSetup& setup = checked_setup(output, map_file, localizer);
  return survey::SurveyEstimator(setup.camera, setup.mount, setup.map, survey::SurveyConfig{});
}

}  // namespace

SurveyWriter::SurveyWriter(const std::filesystem::path& output, const std::filesystem::path& map_file, Localizer& localizer,
                           std::FILE* log,
                           std::chrono::nanoseconds interval)
    : localizer_(localizer),
      log_(log),
      interval_(interval),
      survey_(make_estimator(output, map_file, localizer)),
      file_(output, "irlocd: --survey ", log) {
  established_.reserve(survey::SurveyConfig{}.max_markers + localizer.setup().map.dot_markers.size());
  use_established_markers();
}

// Localization uses the markers the survey has established, each with its current sigma; markers
// not yet established are where the drawing puts them, up to decimetres off: no pose from them.
void SurveyWriter::use_established_markers() {
  survey_.established_markers(established_);
  localizer_.set_dot_markers(established_);
}

void SurveyWriter::on_attempt(const StrobePair& pair, std::optional<StrobeVerdict>, bool computed, const PoseEstimate&) {
  if (!computed) return;
  for (const SourceResult& result : localizer_.last_results()) {
    if (result.kind == SourceKind::dot && result.at_frame_time()) survey_.observe(result.observations);
  }
  if (!survey_.events().empty()) {
    report_events();
    publish();
  }
  use_established_markers();
  if (!last_write_ns_) last_write_ns_ = pair.on.t_ns;
  // A frame clock that went back must not hold the map back until it catches up.
  if (pair.on.t_ns < *last_write_ns_ || pair.on.t_ns - *last_write_ns_ >= interval_.count()) {
    publish();
    last_write_ns_ = pair.on.t_ns;
  }
}

void SurveyWriter::finish() {
  report_events();
  publish();
  file_.wait_until_written();
}

void SurveyWriter::report_events() {
  for (const survey::SurveyEvent& event : survey_.events()) {
    ++counts_[static_cast<std::size_t>(event.kind)];
    const Eigen::Vector3d& a = event.old_origin;
    const Eigen::Vector3d& b = event.new_origin;
    switch (event.kind) {
      case survey::SurveyEvent::Kind::moved:
        std::fprintf(log_, "irlocd: survey: marker %d moved from (%.3f, %.3f, %.3f) to (%.3f, %.3f, %.3f)\n", event.id,
                     a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
        break;
      case survey::SurveyEvent::Kind::added:
        std::fprintf(log_, "irlocd: survey: marker %d added at (%.3f, %.3f, %.3f)\n", event.id, b.x(), b.y(), b.z());
        break;
      case survey::SurveyEvent::Kind::conflict:
        std::fprintf(log_,
                     "irlocd: survey: marker %d seen at two places, (%.3f, %.3f, %.3f) and (%.3f, %.3f, %.3f): left "
                     "out of the map\n",
                     event.id, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
        break;
    }
  }
  survey_.clear_events();
}

void SurveyWriter::publish() { file_.submit(survey_.estimated_map()); }

}  // namespace irloc::firmware
