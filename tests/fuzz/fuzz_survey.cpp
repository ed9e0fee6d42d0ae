// libFuzzer target: irlocd --survey's inputs, the map it starts from and the sightings it learns
// from (algo/survey/survey_estimator), and what it writes. The input is a marker map (YAML) up to
// the first NUL byte, then frames of 4 bytes: the level robot's step (dx, dy up to 5 cm, dyaw up
// to 2 degrees) and a byte that installs an unmapped marker near the robot (bits 7 and 6 set),
// moves one marker by up to 0.24 m (bit 7 alone) or corrupts one dot's pixel (bit 7 clear). Each
// frame sees the installed markers (the map's, as moved, and the unmapped) through the corridor
// tests' 1280 x 960
// camera, with the dots' pixels rounded to 1/16 px. A map irlocd refuses ends the input; otherwise
// the survey must run without a crash or hang, and the map it writes must read back (MAP_OUT is a
// valid input map for the next run: docs/formats.md).
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "algo/survey/survey_estimator.hpp"
#include "io/config/map_file.hpp"
#include "io/files/map_file_writer.hpp"
#include "io/input_error.hpp"
#include "tests/fuzz/fuzz_files.hpp"
#include "tests/survey/corridor.hpp"

namespace {

constexpr std::size_t kMaxFrames = 64;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace irloc;
  const std::uint8_t* end = data + size;
  const std::uint8_t* map_end = std::find(data, end, std::uint8_t{0});
  MarkerMap map;
  try {
    map = io::load_marker_map(fuzz::write_file("map.yaml", std::string(data, map_end)));
  } catch (const io::InputError&) {
    return 0;
  }
  // What irlocd --survey refuses at start-up (firmware/survey_writer.cpp): no fixed dot marker.
  if (std::none_of(map.dot_markers.begin(), map.dot_markers.end(), [](const DotMarker& marker) { return marker.fixed; })) {
    return 0;
  }
  survey::SurveyEstimator survey(test::corridor_camera(), test::corridor_mount(), map, survey::SurveyConfig{});

  std::vector<DotMarker> installed = map.dot_markers;
  std::mt19937 noise(7);
  double x = 0, y = 0, yaw = 0;
  std::size_t frames = 0;
  for (const std::uint8_t* at = map_end == end ? end : map_end + 1; at + 4 <= end && frames < kMaxFrames; at += 4, ++frames) {
    x += static_cast<std::int8_t>(at[0]) * 0.05 / 128;
    y += static_cast<std::int8_t>(at[1]) * 0.05 / 128;
    yaw += static_cast<std::int8_t>(at[2]) * 0.035 / 128;
    const std::uint8_t change = at[3];
    if ((change & 0xc0) == 0xc0) {
      const int id = change * 37 % (dot::kMaxMarkerId + 1);
      if (std::none_of(installed.begin(), installed.end(), [&](const DotMarker& marker) { return marker.id == id; })) {
        // Made in place: copying a DotMarker with its empty optional sigma trips GCC 12's
        // maybe-uninitialized at -O2.
        DotMarker& unmapped = installed.emplace_back();
        unmapped.id = id;
        unmapped.origin = {x + (change % 8) * 0.1, y + 0.4, 2.6};
      }
    } else if ((change & 0x80) != 0 && !installed.empty()) {
      DotMarker& moved = installed[change % installed.size()];
      moved.origin.x() += ((change >> 2) % 16 - 8) * 0.03;
    }
    PointObservationList observations = test::observe(installed, x, y, yaw, 0.05, noise);
    for (PointObservation& dot : observations) dot.pixel = (dot.pixel * 16).array().round() / 16;
    if ((change & 0x80) == 0 && !observations.empty()) observations[change % observations.size()].pixel.x() += change;
    survey.observe(observations);
    survey.clear_events();
  }

  const std::filesystem::path written = fuzz::folder() / "survey.yaml";
  io::write_marker_map(written, survey.estimated_map());
  try {
    io::load_marker_map(written);
  } catch (const io::InputError&) {
    std::abort();  // the survey wrote a map it cannot read back
  }
  return 0;
}
