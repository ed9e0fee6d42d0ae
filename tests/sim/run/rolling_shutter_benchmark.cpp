// The time the rolling-shutter correction adds to a frame (issue 29: at most 10 %): the pipeline
// (Localizer::process) over a rendered drive at the default board's mode
// (host_sim/scenarios/dot_rolling_board.yaml: 820x616, 37.8 us a row, 1 m/s, 90 deg/s), once with
// the line time (the dot source moves its points to t_ns and refits) and once with the same frames
// taken for a global shutter. The frames are rendered once, outside the timing, and kept in
// memory; the timed loop cycles through their pairs with frame times running on, so the track
// stays alive. Counters: ms_per_frame (mean), ms_pose (the dot source's pose stage), posed_fraction;
// ms_per_tracked_frame and ms_pose_tracked over the attempts with a track (not the first three of a
// lap, which follow the jump back to the drive's start: there the track is refused and the frames
// solved as with no motion known, the dearer paths a drive takes once, at its start).
//
// On a shared machine the times vary with the load by more than the correction costs; the
// instructions do not. Under callgrind (valgrind --tool=callgrind --instr-atstart=no) each run of
// the timed loop is dumped apart, named `corrected` or `global` (callgrind_annotate gives its
// instructions and its calls of Localizer::process); with IRLOC_BENCH_TRACKED_ONLY set, only the
// attempts with a track are collected. IRLOC_BENCH_DATASET names a folder to render the drive
// into once and read it from afterwards (callgrind would take many minutes over the render).

#include <benchmark/benchmark.h>
#include <valgrind/callgrind.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "algo/core/image.hpp"
#include "algo/frames/strobe_pairer.hpp"
#include "algo/pipeline/localizer.hpp"
#include "io/config/config_file.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::sim {
namespace {

constexpr int kFrames = 40;

struct Drive {
  LocalizerSetup setup;
  std::vector<Image8> images;
  std::vector<Frame> frames;  // viewing `images`
  std::int64_t duration_ns = 0;
};

const Drive& drive() {
  static const Drive rendered = [] {
    Scenario scenario = load_scenario(std::filesystem::path(IRLOC_SCENARIOS_DIR) / "dot_rolling_board.yaml");
    scenario.frames = kFrames;
    const char* kept = std::getenv("IRLOC_BENCH_DATASET");
    test::TempDir temporary;
    const std::filesystem::path dir = kept != nullptr ? std::filesystem::path(kept) : temporary.path();
    if (!std::filesystem::exists(dir / "config.yaml")) render_dataset(scenario, dir);
    Drive d;
    io::RobotConfig config = io::load_robot_config(dir / "config.yaml");
    d.setup = config.setup;
    hal::DatasetCamera camera(dir, d.setup.camera.width, d.setup.camera.height, "calib.yaml");
    Frame frame;
    while (camera.next(frame)) {
      const ImageView8 view = std::get<ImageView8>(frame.image);
      Image8 copy(view.width(), view.height());
      for (int y = 0; y < view.height(); ++y) std::copy(view.row(y), view.row(y) + view.width(), copy.view().row(y));
      d.images.push_back(std::move(copy));
      d.frames.push_back(frame);
    }
    for (std::size_t i = 0; i < d.frames.size(); ++i) d.frames[i].image = ImageView8(d.images[i].view());
    d.duration_ns = d.frames.back().t_ns - d.frames.front().t_ns + (d.frames[1].t_ns - d.frames[0].t_ns);
    return d;
  }();
  return rendered;
}

void pipeline(benchmark::State& state, bool rolling) {
  const Drive& d = drive();
  LocalizerSetup setup = d.setup;
  if (!rolling) setup.line_time_ns = 0;
  Localizer localizer(setup);
  std::map<std::string, double> stage_sums;
  // Over the attempts with a track: the fourth and later of a lap, the three before them posed (the
  // lap's first attempt follows the jump back to the drive's start, where a robot would have been
  // carried: the track is refused and the frame solved as without motion; the second follows that
  // plain pose, the third has a last pose but no track yet).
  double tracked_sum = 0, tracked_pose_sum = 0;
  std::int64_t tracked = 0, lap_attempts = 0, posed_in_row = 0, current_lap = -1;
  std::int64_t attempts = 0, posed = 0, lap = 0;
  std::size_t next = 0;
  StrobePairer pairer;
  const bool collect_tracked_only = std::getenv("IRLOC_BENCH_TRACKED_ONLY") != nullptr;
  CALLGRIND_START_INSTRUMENTATION;
  CALLGRIND_ZERO_STATS;
  for (auto _ : state) {
    // The next pair of the drive, its times one lap on each time round.
    std::optional<StrobePair> pair;
    std::int64_t pair_lap = lap;  // of the pair's last frame
    while (!pair) {
      Frame frame = d.frames[next];
      frame.t_ns += lap * d.duration_ns;
      pair_lap = lap;
      pair = pairer.push(frame);
      if (++next == d.frames.size()) {
        next = 0;
        ++lap;
      }
    }
    lap_attempts = pair_lap == current_lap ? lap_attempts + 1 : 1;
    current_lap = pair_lap;
    const bool with_track = lap_attempts >= 4 && posed_in_row >= 3;
    const bool left_out = collect_tracked_only && !with_track;
    if (left_out) CALLGRIND_TOGGLE_COLLECT;
    const PoseEstimate estimate = localizer.process(*pair);
    if (left_out) CALLGRIND_TOGGLE_COLLECT;
    benchmark::DoNotOptimize(estimate);
    ++attempts;
    posed += estimate.ok ? 1 : 0;
    posed_in_row = estimate.ok ? posed_in_row + 1 : 0;
    for (const StageTime& stage : localizer.last_stage_times()) {
      stage_sums[stage.name] += stage.milliseconds;
      if (!with_track) continue;
      tracked_sum += stage.milliseconds;
      if (stage.name == std::string_view("pose")) tracked_pose_sum += stage.milliseconds;
    }
    tracked += with_track ? 1 : 0;
  }
  CALLGRIND_DUMP_STATS_AT(rolling ? "corrected" : "global");
  CALLGRIND_STOP_INSTRUMENTATION;
  const auto n = static_cast<double>(attempts);
  double total = 0;
  for (const auto& [name, sum] : stage_sums) total += sum;
  state.counters["ms_per_frame"] = total / n;
  state.counters["ms_pose"] = stage_sums["pose"] / n;
  state.counters["posed_fraction"] = static_cast<double>(posed) / n;
  state.counters["ms_per_tracked_frame"] = tracked_sum / static_cast<double>(std::max<std::int64_t>(tracked, 1));
  state.counters["ms_pose_tracked"] = tracked_pose_sum / static_cast<double>(std::max<std::int64_t>(tracked, 1));
}

void BM_DotPipeline_820x616_RollingShutterCorrected(benchmark::State& state) { pipeline(state, true); }
void BM_DotPipeline_820x616_TakenForGlobalShutter(benchmark::State& state) { pipeline(state, false); }

BENCHMARK(BM_DotPipeline_820x616_RollingShutterCorrected)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DotPipeline_820x616_TakenForGlobalShutter)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc::sim

BENCHMARK_MAIN();
