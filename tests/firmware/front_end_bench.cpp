// The Localizer's front-end stage as irlocd runs it, beside a memcpy of the same frame pair in the
// same run. Each size and depth renders a short drive of host_sim/scenarios/dot_cluttered.yaml
// (dot markers, a square tape marker, four lamps, a sunny window, people) with stray reflectors
// added, at that size and depth, loads its config.yaml with irlocd's reader and its frames with
// irlocd's dataset camera, then times Localizer::process on its pairs in turn.
//
// FrontEnd/WxH/bits: the time is the attempt's `front_end` stages (the shared pass and any
// relabelling a source asks for), as irlocd's --stats sums them; counters: the medians of the
// front end and of the pair's memcpy (us), their ratio (the goal: <= 2), relabellings per pair,
// and the share of pairs the shared pass labelled twice (first at the expected threshold).
// read_pair_us: the least any pass over the pair costs (every byte read once, nothing written).
// DotAttempt/1280x960/8: the dot path alone (the config's square marker left out): the median
// wall time of the whole attempt, the median sum of its reported stage times and their ratio, and
// each stage's median.
// TapeMask/WxH/8bit: the square source's tape mask from the shared pass's runs and from its own
// pass over the pair; OutsideInBackground/WxH/8bit: the outside-in background model on a frame
// (foreground_share: the median share of its pixels found foreground); each beside memcpy of what
// it reads.
// `make bench` writes build/bench/front_end.json.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "algo/core/image.hpp"
#include "algo/kernels/pair_pass.hpp"
#include "algo/markers/outside_in/adaptive_background.hpp"
#include "algo/markers/square/tape_mask.hpp"
#include "algo/pipeline/localizer.hpp"
#include "firmware/front_end_probe.hpp"
#include "io/config/config_file.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "host_sim/render/dataset_render.hpp"
#include "host_sim/scenario/scenario.hpp"
#include "tests/support/median.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc {
namespace {

using Clock = std::chrono::steady_clock;
using test::median;

constexpr int kFrames = 8;  // four strobe pairs along the drive
constexpr int kFrontEndAttempts = 200;

struct Drive {
  io::RobotConfig config;
  std::vector<Image8> frames8;
  std::vector<Image16> frames16;
  std::vector<StrobePair> pairs;
};

// dot_cluttered.yaml at width x height (the same field of view) and bit_depth, kFrames frames,
// one ray per pixel, no dropped frames, with a strip and two crescents of stray reflective
// material beside the markers.
sim::Scenario drive_scenario(int width, int height, int bit_depth) {
  sim::Scenario scenario = sim::load_scenario(std::string(IRLOC_SCENARIOS_DIR) + "/dot_cluttered.yaml");
  CameraIntrinsics& lens = scenario.camera.intrinsics;
  const double scale = static_cast<double>(width) / lens.width;
  lens.fx *= scale;
  lens.fy *= scale;
  lens.cx = (width - 1) / 2.0;
  lens.cy = (height - 1) / 2.0;
  lens.width = width;
  lens.height = height;
  scenario.camera.bit_depth = bit_depth;
  scenario.frames = kFrames;
  scenario.supersampling = 1;
  scenario.motion_blur_samples = 1;
  scenario.dropped_frames.clear();
  scenario.drop_probability = 0;
  using Kind = sim::CeilingClutter::Kind;
  scenario.room.clutter = {{Kind::strip, {-0.9, -0.8}, 0.3, 0.6, 0.04, 0},
                           {Kind::crescent, {-0.6, -1.0}, 1.0, 0, 0, 0.02},
                           {Kind::crescent, {-1.3, -0.5}, -2.0, 0, 0, 0.03}};
  return scenario;
}

template <typename Pixel>
Image<Pixel> copy_of(ImageView<const Pixel> view) {
  Image<Pixel> image(view.width(), view.height());
  for (int y = 0; y < view.height(); ++y) std::copy_n(view.row(y), view.width(), image.view().row(y));
  return image;
}

// Frames owned here, paired as the dataset labels them.
std::unique_ptr<Drive> render_drive(int width, int height, int bit_depth) {
  const test::TempDir dir;
  sim::render_dataset(drive_scenario(width, height, bit_depth), dir.path());
  auto drive = std::make_unique<Drive>();
  drive->config = io::load_robot_config(dir / "config.yaml");
  hal::DatasetCamera camera(dir.path(), width, height, "the benchmark");
  std::vector<Frame> frames;
  for (Frame frame; camera.next(frame);) {
    if (const auto* view = std::get_if<ImageView8>(&frame.image)) {
      drive->frames8.push_back(copy_of(*view));
    } else {
      drive->frames16.push_back(copy_of(std::get<ImageView16>(frame.image)));
    }
    frames.push_back(frame);
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].image = bit_depth == 8 ? GrayImageView(ImageView8(drive->frames8[i].view()))
                                     : GrayImageView(ImageView16(drive->frames16[i].view()));
  }
  StrobePairer pairer;
  for (const Frame& frame : frames) {
    if (std::optional<StrobePair> pair = pairer.push(frame); pair && pair->off) drive->pairs.push_back(*pair);
  }
  return drive;
}

// Rendered once per size and depth, shared by every run of a case.
const Drive& drive_of(int width, int height, int bit_depth) {
  static std::map<std::tuple<int, int, int>, std::unique_ptr<Drive>> drives;
  std::unique_ptr<Drive>& drive = drives[{width, height, bit_depth}];
  if (!drive) drive = render_drive(width, height, bit_depth);
  return *drive;
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The least any pass over a frame costs: every byte read once, nothing written (the OR of its words,
// which the compiler vectorizes).
std::uint64_t read_all(const void* data, std::size_t bytes) {
  std::uint64_t any = 0;
  const auto* bytes_in = static_cast<const unsigned char*>(data);
  for (std::size_t offset = 0; offset + 8 <= bytes; offset += 8) {
    std::uint64_t word;
    std::memcpy(&word, bytes_in + offset, sizeof word);
    any |= word;
  }
  return any;
}

const void* data_of(const GrayImageView& image) {
  return std::visit([](const auto& view) -> const void* { return view.data(); }, image);
}

void front_end(benchmark::State& state, int width, int height, int bit_depth) {
  const Drive& drive = drive_of(width, height, bit_depth);
  if (drive.pairs.empty()) {
    state.SkipWithError("the rendered drive has no strobe pair");
    return;
  }
  Localizer localizer(drive.config.setup);
  const std::size_t pair_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * (bit_depth == 8 ? 1 : 2);
  std::vector<std::byte> on_copy(pair_bytes), off_copy(pair_bytes);
  std::vector<double> front_end_s, memcpy_s, read_s;
  std::uint64_t relabels = 0, labelled_twice = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const StrobePair& pair = drive.pairs[next++ % drive.pairs.size()];
    benchmark::DoNotOptimize(localizer.process(pair));
    const double front = firmware::front_end_total_ms(localizer.last_stage_times()) * 1e-3;
    relabels += localizer.last_pair_analysis().relabels;
    labelled_twice += localizer.last_pair_analysis().labelled_twice ? 1 : 0;
    // The copy comes second, so it finds the pair as warm in the caches as the front end left it.
    const Clock::time_point copy_start = Clock::now();
    std::memcpy(on_copy.data(), data_of(pair.on.image), pair_bytes);
    std::memcpy(off_copy.data(), data_of(pair.off->image), pair_bytes);
    benchmark::ClobberMemory();
    memcpy_s.push_back(seconds_since(copy_start));
    const Clock::time_point read_start = Clock::now();
    benchmark::DoNotOptimize(read_all(data_of(pair.on.image), pair_bytes) | read_all(data_of(pair.off->image), pair_bytes));
    read_s.push_back(seconds_since(read_start));
    front_end_s.push_back(front);
    state.SetIterationTime(front);
  }
  const double front_median = median(front_end_s);
  const double memcpy_median = median(memcpy_s);
  state.counters["front_end_us"] = front_median * 1e6;
  state.counters["memcpy_pair_us"] = memcpy_median * 1e6;
  state.counters["ratio"] = memcpy_median > 0 ? front_median / memcpy_median : 0;
  state.counters["read_pair_us"] = median(read_s) * 1e6;
  state.counters["relabels_per_pair"] = static_cast<double>(relabels) / static_cast<double>(state.iterations());
  state.counters["labelled_twice_per_pair"] = static_cast<double>(labelled_twice) / static_cast<double>(state.iterations());
  const PairAnalysis& last = localizer.last_pair_analysis();
  state.counters["blobs"] = static_cast<double>(last.blobs.size());
  state.counters["runs"] = last.blob_counters.runs;
  state.counters["foreground_px"] = last.blob_counters.foreground_pixels;
  state.counters["threshold"] = last.threshold;
}

void dot_attempt(benchmark::State& state, int width, int height) {
  const Drive& drive = drive_of(width, height, 8);
  LocalizerSetup setup = drive.config.setup;
  setup.map.square_markers.clear();
  Localizer localizer(setup);
  std::vector<double> attempt_s, stages_s;
  std::map<std::string, std::vector<double>> stage_ms;
  std::int64_t found = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const StrobePair& pair = drive.pairs[next++ % drive.pairs.size()];
    const Clock::time_point start = Clock::now();
    const PoseEstimate estimate = localizer.process(pair);
    const double attempt = seconds_since(start);
    benchmark::DoNotOptimize(estimate);
    found += estimate.ok ? 1 : 0;
    double stages = 0;
    for (const StageTime& stage : localizer.last_stage_times()) {
      stages += stage.milliseconds * 1e-3;
      stage_ms[stage.name].push_back(stage.milliseconds);
    }
    attempt_s.push_back(attempt);
    stages_s.push_back(stages);
    state.SetIterationTime(attempt);
  }
  const double attempt_median = median(attempt_s);
  state.counters["attempt_ms"] = attempt_median * 1e3;
  state.counters["stages_ms"] = median(stages_s) * 1e3;
  state.counters["stages_per_attempt"] = attempt_median > 0 ? median(stages_s) / attempt_median : 0;
  state.counters["found_fraction"] = static_cast<double>(found) / static_cast<double>(state.iterations());
  for (const auto& [name, times] : stage_ms) state.counters["median_ms_" + name] = median(times);
}

// The square source's tape mask (a 4 px element) from the shared pass's runs, as irlocd makes it
// when the tape threshold is the blobs', and from its own pass over the pair (another threshold),
// beside memcpy of the pair.
void tape_mask(benchmark::State& state, int width, int height) {
  const Drive& drive = drive_of(width, height, 8);
  PairPassConfig config;
  config.front_end.width = width;
  config.front_end.height = height;
  PairPass pass(config);
  square::TapeMask mask(0, 0, width, height, 4, 8);
  const std::size_t pair_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::byte> on_copy(pair_bytes), off_copy(pair_bytes);
  std::vector<double> shared_s, own_s, memcpy_s;
  std::size_t next = 0;
  for (auto _ : state) {
    const StrobePair& pair = drive.pairs[next++ % drive.pairs.size()];
    const PairAnalysis& analysis = pass.analyse(pair.on.image, pair.off->image);
    Clock::time_point start = Clock::now();
    mask.extract(pass.foreground_runs());
    benchmark::DoNotOptimize(mask.mask());
    shared_s.push_back(seconds_since(start));
    start = Clock::now();
    mask.extract(pair.on.image, pair.off->image, static_cast<std::uint16_t>(analysis.threshold));
    benchmark::DoNotOptimize(mask.mask());
    own_s.push_back(seconds_since(start));
    start = Clock::now();
    std::memcpy(on_copy.data(), data_of(pair.on.image), pair_bytes);
    std::memcpy(off_copy.data(), data_of(pair.off->image), pair_bytes);
    benchmark::ClobberMemory();
    memcpy_s.push_back(seconds_since(start));
    state.SetIterationTime(shared_s.back());
  }
  state.counters["from_runs_us"] = median(shared_s) * 1e6;
  state.counters["own_pass_us"] = median(own_s) * 1e6;
  state.counters["memcpy_pair_us"] = median(memcpy_s) * 1e6;
}

// The outside-in source's background model on one frame (8 bit) beside memcpy of the frame. The
// frames are the drive's LED-on frames, a ceiling rather than a floor: the model's work per pixel
// is the same.
void outside_in_background(benchmark::State& state, int width, int height) {
  const Drive& drive = drive_of(width, height, 8);
  outside_in::AdaptiveBackgroundConfig config;
  config.width = width;
  config.height = height;
  outside_in::AdaptiveBackground background(config);
  Image8 foreground(width, height);
  const std::size_t frame_bytes = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::byte> copy(frame_bytes);
  std::vector<double> background_s, memcpy_s, foreground_share;
  std::size_t next = 0;
  for (auto _ : state) {
    const StrobePair& pair = drive.pairs[next++ % drive.pairs.size()];
    const ImageView8 frame = std::get<ImageView8>(pair.on.image);
    Clock::time_point start = Clock::now();
    const outside_in::BackgroundStep step = background.apply(frame, foreground.view(), outside_in::ProtectedRects{});
    background_s.push_back(seconds_since(start));
    foreground_share.push_back(static_cast<double>(step.foreground_pixels) / static_cast<double>(frame_bytes));
    start = Clock::now();
    std::memcpy(copy.data(), frame.data(), frame_bytes);
    benchmark::ClobberMemory();
    memcpy_s.push_back(seconds_since(start));
    state.SetIterationTime(background_s.back());
  }
  const double background_median = median(background_s);
  const double memcpy_median = median(memcpy_s);
  state.counters["background_us"] = background_median * 1e6;
  state.counters["memcpy_frame_us"] = memcpy_median * 1e6;
  state.counters["ratio"] = memcpy_median > 0 ? background_median / memcpy_median : 0;
  state.counters["foreground_share"] = median(foreground_share);
}

void register_benchmarks() {
  struct Size {
    int width, height;
  };
  for (const Size size : {Size{640, 480}, Size{820, 616}, Size{1280, 960}, Size{1456, 1088}}) {
    for (const int bits : {8, 12}) {
      const std::string name = "FrontEnd/" + std::to_string(size.width) + "x" + std::to_string(size.height) + "/" +
                               (bits == 8 ? "8bit" : "16bit");
      // A fixed count: each attempt also runs the square source, many times the front end's time.
      benchmark::RegisterBenchmark(name.c_str(), front_end, size.width, size.height, bits)
          ->Iterations(kFrontEndAttempts)
          ->UseManualTime()
          ->Unit(benchmark::kMicrosecond);
    }
  }
  benchmark::RegisterBenchmark("DotAttempt/1280x960/8bit", dot_attempt, 1280, 960)
      ->UseManualTime()
      ->Unit(benchmark::kMillisecond);
  for (const Size size : {Size{640, 480}, Size{1280, 960}}) {
    const std::string suffix = std::to_string(size.width) + "x" + std::to_string(size.height) + "/8bit";
    benchmark::RegisterBenchmark(("TapeMask/" + suffix).c_str(), tape_mask, size.width, size.height)
        ->UseManualTime()
        ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("OutsideInBackground/" + suffix).c_str(), outside_in_background, size.width, size.height)
        ->UseManualTime()
        ->Unit(benchmark::kMicrosecond);
  }
}

}  // namespace
}  // namespace irloc

int main(int argc, char** argv) {
  irloc::register_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
