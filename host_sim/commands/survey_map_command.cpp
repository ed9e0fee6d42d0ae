// irloc-sim survey-map: a surveyed map against the truth (errors), or against the map it started
// from (moves), printed per marker and drawn from above.

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "algo/geometry/pose.hpp"
#include "io/config/map_file.hpp"
#include "io/files/run_files.hpp"
#include "host_sim/commands/commands.hpp"
#include "host_sim/plots/plots.hpp"
#include "host_sim/tools/survey_check.hpp"

namespace irloc::sim {
namespace {

constexpr double kDegrees = 180 / std::numbers::pi;

// A real run: each marker against where the survey started from.
void print_moves(const MarkerMap& drawing, const MarkerMap& estimate, const std::string& out) {
  for (const DotMarker& marker : estimate.dot_markers) {
    const DotMarker* before = drawing.find_dot_marker(marker.id);
    if (before == nullptr) {
      std::printf("marker %4d: new\n", marker.id);
    } else {
      std::printf("marker %4d: moved %7.2f mm %7.3f deg\n", marker.id, 1e3 * (marker.origin - before->origin).norm(),
                  std::abs(wrap_angle(marker.yaw - before->yaw)) * kDegrees);
    }
  }
  std::printf("irloc-sim survey-map: %zu markers before, %zu after; picture in %s\n", drawing.dot_markers.size(),
              estimate.dot_markers.size(), out.c_str());
}

// A rendered run: each marker against the truth.
void print_errors(const MarkerMap& estimate, const MarkerMap& truth, const std::string& out) {
  const SurveyCheck check = check_survey(estimate, truth);
  for (const SurveyMarkerError& marker : check.markers) {
    std::printf("marker %4d: %7.2f mm %7.3f deg\n", marker.id, 1e3 * marker.position_m, marker.yaw_rad * kDegrees);
  }
  for (const int id : check.unknown) std::printf("marker %4d: unknown (no sighting measured it)\n", id);
  std::printf("irloc-sim survey-map: %zu markers, max %.2f mm, %.3f deg; unknown %zu, missing %zu, invented %zu; "
              "picture in %s\n",
              check.markers.size(), 1e3 * check.max_position_m, check.max_yaw_rad * kDegrees, check.unknown.size(),
              check.missing.size(), check.invented.size(), out.c_str());
}

}  // namespace

void add_survey_map_command(CommandLine& command_line) {
  struct Options {
    std::string drawing, estimate, truth, out;
  };
  auto options = std::make_shared<Options>();
  Subcommand command = command_line.add(
      "survey-map", "a surveyed map against the truth (errors), or against the map it started from (moves): a top-view picture");
  command.text("--drawing", options->drawing, "the map the survey started from", Need::required);
  command.text("--estimate", options->estimate, "the map irlocd --survey wrote", Need::required);
  command.text("--truth", options->truth, "the true map (a rendered dataset's map.yaml); without it (a real run), the moves");
  command.text("--out", options->out, "PNG to write", Need::required);
  command.action([options] {
    io::RunFiles files;
    files.inputs({options->drawing, options->estimate});
    if (!options->truth.empty()) files.input(options->truth);
    files.output_file("--out", options->out);
    files.check();
    const MarkerMap drawing = io::load_marker_map(options->drawing);
    const MarkerMap estimate = io::load_marker_map(options->estimate);
    if (options->truth.empty()) {
      print_moves(drawing, estimate, options->out);
      plot_survey_map(options->out, drawing, estimate, nullptr);
    } else {
      const MarkerMap truth = io::load_marker_map(options->truth);
      print_errors(estimate, truth, options->out);
      plot_survey_map(options->out, drawing, estimate, &truth);
    }
  });
}

}  // namespace irloc::sim
