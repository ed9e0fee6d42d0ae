// Per-frame time of the outside-in source, stage by stage, beside memcpy of the frame, at 640 x 480
// (the goal's webcam) and 1280 x 720 (the same room and vertical field of view, f 750 px).
// Once per size a drive of the goal's room is rendered: the empty floor, then the robot on the goal's
// ellipse with a person crossing in front of it, the sun patch drifting and auto-exposure on. The
// source learns it once, then replays it forward and back (the robot reverses at the ends), so the
// robot stays tracked and every timed frame runs background, components and the box fit.
// Counters, medians over the timed frames in microseconds: `background_us`, `components_us`,
// `box_fit_us` (the source's stage times), `total_us` (the whole process() call), `memcpy_us` (the
// frame copied right after), their ratio `total_vs_memcpy`, `total_cpu_us` (the process() call's
// CPU time on its thread: on a loaded machine the wall times include waits for a core), and
// `pose_rate`.
#include <benchmark/benchmark.h>


#include <chrono>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "tests/outside_in/outside_in_drive.hpp"
#include "tests/support/median.hpp"
#include "tests/support/thread_cpu_time.hpp"

namespace irloc::test {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kDriveFrames = 40;
constexpr double kFps = 10;

// The goal's wall camera at another resolution: f scaled with the height, so the rows see the same
// floor and a wider image sees more of it sideways.
WallCamera camera_of(int width, int height) {
  WallCamera camera;
  const double f = camera.intrinsics.fy * height / camera.intrinsics.height;
  camera.intrinsics = CameraIntrinsics{width, height, f, f, (width - 1) / 2.0, (height - 1) / 2.0, LensModel::plumb_bob, {}};
  return camera;
}

SceneState drive_scene(int i) {
  SceneState scene;
  if (i == 0) return scene;  // the empty floor: the background starts without a ghost
  scene.robot = ellipse_pose(i / kFps, 2.4);
  if (i >= 15 && i < 30) scene.person = Person{Eigen::Vector2d(3.6 - 0.02 * (i - 15), 1.8 - 0.16 * (i - 15))};
  scene.sun = Eigen::Vector2d(3.0 + 0.01 * i, 1.2);
  return scene;
}

double stage_ms(const SourceResult& result, std::string_view name) {
  for (const StageTime& stage : result.times)
    if (name == stage.name) return stage.milliseconds;
  return 0;
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void outside_in_frame(benchmark::State& state, int width, int height) {
  OutsideInRig rig(camera_of(width, height));
  SceneRenderer renderer(rig.camera);
  std::vector<std::vector<std::uint8_t>> frames;
  for (int i = 0; i < kDriveFrames; ++i) {
    FrameTruth truth;
    frames.push_back(renderer.render(drive_scene(i), truth));
  }
  const auto frame_at = [&](std::int64_t i, std::size_t index) {
    return Frame{static_cast<std::uint64_t>(i), i * static_cast<std::int64_t>(1e9 / kFps), false,
                 ImageView8(frames[index].data(), width, height)};
  };
  SourceResult result;
  std::int64_t i = 0;
  for (; i < kDriveFrames; ++i) rig.source->process({frame_at(i, static_cast<std::size_t>(i)), nullptr}, result);
  std::vector<std::uint8_t> copy(frames[0].size());
  std::vector<double> background_ms, components_ms, box_fit_ms, total_s, total_cpu_s, memcpy_s;
  int poses = 0;
  for (auto _ : state) {
    // Back from the last frame to frame 1, then forward again (frame 0 is the empty floor).
    const std::int64_t period = 2 * (kDriveFrames - 2);
    const std::int64_t phase = (i - kDriveFrames) % period;
    const std::size_t index = static_cast<std::size_t>(phase < kDriveFrames - 2 ? kDriveFrames - 2 - phase : phase - (kDriveFrames - 4));
    const Frame frame = frame_at(i++, index);
    const double cpu_start = thread_cpu_seconds();
    Clock::time_point start = Clock::now();
    rig.source->process({frame, nullptr}, result);
    total_s.push_back(seconds_since(start));
    total_cpu_s.push_back(thread_cpu_seconds() - cpu_start);
    start = Clock::now();
    std::memcpy(copy.data(), frames[index].data(), copy.size());
    benchmark::ClobberMemory();
    memcpy_s.push_back(seconds_since(start));
    state.SetIterationTime(total_s.back());
    background_ms.push_back(stage_ms(result, "background"));
    components_ms.push_back(stage_ms(result, "components"));
    box_fit_ms.push_back(stage_ms(result, "box_fit"));
    poses += result.ok;
  }
  const double total = median(total_s), memcpy_median = median(memcpy_s);
  state.counters["background_us"] = median(background_ms) * 1e3;
  state.counters["components_us"] = median(components_ms) * 1e3;
  state.counters["box_fit_us"] = median(box_fit_ms) * 1e3;
  state.counters["total_us"] = total * 1e6;
  state.counters["total_cpu_us"] = median(total_cpu_s) * 1e6;
  state.counters["memcpy_us"] = memcpy_median * 1e6;
  state.counters["total_vs_memcpy"] = memcpy_median > 0 ? total / memcpy_median : 0;
  state.counters["pose_rate"] = static_cast<double>(poses) / std::max<double>(static_cast<double>(state.iterations()), 1);
}

void register_benchmarks() {
  for (const auto& [width, height] : {std::pair{640, 480}, std::pair{1280, 720}}) {
    const std::string name = "OutsideInFrame/" + std::to_string(width) + "x" + std::to_string(height);
    benchmark::RegisterBenchmark(name.c_str(), outside_in_frame, width, height)
        ->UseManualTime()
        ->Unit(benchmark::kMicrosecond);
  }
}

}  // namespace
}  // namespace irloc::test

int main(int argc, char** argv) {
  irloc::test::register_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
