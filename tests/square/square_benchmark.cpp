// Per-frame time of the square path at the goal's 1280 x 1024 (goal: 1 ms), whole and by stage,
// on a ray-cast equisolid frame pair with the robot 1.5 m off the square's centre; and the whole
// path for a tilting robot (dof 6: the robot also rolled 3 and pitched -2 degrees). The detector
// alone (its own pass over the pair) and the whole frame in the Localizer (the shared pass, then
// the square source).

#include <benchmark/benchmark.h>

#include <map>
#include <numbers>
#include <string>

#include "algo/markers/square/square_detector.hpp"
#include "algo/markers/square/square_marker_source.hpp"
#include "algo/pipeline/localizer.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

constexpr double kDegree = std::numbers::pi / 180;

struct Fixture {
  TapeScene scene;
  Image8 on, off;
  SquareDetector detector;
  DifferenceNoise noise;         // the pair's shared estimate
  std::uint16_t threshold = 0;   // the tape threshold the detector derives from it

  explicit Fixture(Dof dof)
      : scene(make_scene(dof)),
        detector(scene.camera, 8, to_rigid(scene.mount), dof, scene.marker, SquareConfig{}) {
    scene.render(on, off);
    noise = shared_noise(ImageView8(on.view()), ImageView8(off.view()));
    threshold = detector.detect(ImageView8(on.view()), ImageView8(off.view()), noise).threshold;
  }
  static TapeScene make_scene(Dof dof) {
    TapeScene scene;
    scene.camera = fisheye(1280, 1024);
    scene.samples = 2;
    scene.x = 1.2;
    scene.y = -0.9;
    scene.yaw = 0.6;
    if (dof == Dof::full6) {
      scene.roll = 3 * kDegree;
      scene.pitch = -2 * kDegree;
    }
    return scene;
  }
};

Fixture& fixture() {
  static Fixture instance(Dof::planar3);
  return instance;
}

Fixture& tilted_fixture() {
  static Fixture instance(Dof::full6);
  return instance;
}

void detect_each_iteration(benchmark::State& state, Fixture& f) {
  for (auto _ : state) {
    SquareDetection detection = f.detector.detect(ImageView8(f.on.view()), ImageView8(f.off.view()), f.noise);
    benchmark::DoNotOptimize(detection);
    if (!detection.found()) state.SkipWithError("square not found");
  }
}

void BM_SquareDetectTilted(benchmark::State& state) { detect_each_iteration(state, tilted_fixture()); }
BENCHMARK(BM_SquareDetectTilted)->Unit(benchmark::kMillisecond);

void BM_SquareDetect(benchmark::State& state) { detect_each_iteration(state, fixture()); }
BENCHMARK(BM_SquareDetect)->Unit(benchmark::kMillisecond);

// The whole frame as irlocd runs it: the Localizer's one shared pass over the pair (noise,
// threshold, foreground runs, blobs, strobe counts), then the square source on it. Counters: the
// mean time of each stage (ms) and whether the tape mask came from the shared pass.
void localizer_each_iteration(benchmark::State& state, Fixture& f, Dof dof) {
  LocalizerSetup setup;
  setup.camera = f.scene.camera;
  setup.mount = to_rigid(f.scene.mount);
  setup.dof = dof;
  setup.map.square_markers.push_back(f.scene.marker);
  Localizer localizer(setup);
  StrobePair pair;
  pair.on = Frame{.seq = 1, .t_ns = 1000, .led_on = true, .image = ImageView8(f.on.view())};
  pair.off = Frame{.seq = 0, .t_ns = 900, .led_on = false, .image = ImageView8(f.off.view())};
  std::map<std::string, double> stage_sums;
  for (auto _ : state) {
    const PoseEstimate estimate = localizer.process(pair);
    benchmark::DoNotOptimize(estimate);
    if (!estimate.ok) state.SkipWithError("square not found");
    for (const StageTime& stage : localizer.last_stage_times()) stage_sums[stage.name] += stage.milliseconds;
  }
  const auto n = static_cast<double>(state.iterations());
  for (const auto& [name, sum] : stage_sums) state.counters[std::string("ms_") + name] = sum / n;
  state.counters["mask_from_shared_pass"] =
      localizer.find_source<SquareMarkerSource>()->last_diagnostics().mask_from_shared_pass ? 1 : 0;
}

void BM_SquareLocalizer(benchmark::State& state) { localizer_each_iteration(state, fixture(), Dof::planar3); }
BENCHMARK(BM_SquareLocalizer)->Unit(benchmark::kMillisecond);

void BM_SquareLocalizerTilted(benchmark::State& state) {
  localizer_each_iteration(state, tilted_fixture(), Dof::full6);
}
BENCHMARK(BM_SquareLocalizerTilted)->Unit(benchmark::kMillisecond);

void BM_SquareTapeMask(benchmark::State& state) {
  Fixture& f = fixture();
  const CeilingPlaneMap::Region& region = f.detector.plane().mapped_region();
  TapeMask mask(region.x, region.y, region.width, region.height, f.detector.element_radius(), 8);
  for (auto _ : state) {
    mask.extract(ImageView8(f.on.view()), ImageView8(f.off.view()), f.threshold);
    benchmark::DoNotOptimize(mask.mask().row(0));
  }
}
BENCHMARK(BM_SquareTapeMask)->Unit(benchmark::kMillisecond);

void BM_SquareAfterMask(benchmark::State& state) {
  Fixture& f = fixture();
  const CeilingPlaneMap::Region& region = f.detector.plane().mapped_region();
  TapeMask mask(region.x, region.y, region.width, region.height, f.detector.element_radius(), 8);
  mask.extract(ImageView8(f.on.view()), ImageView8(f.off.view()), f.threshold);
  for (auto _ : state) {
    SquareDetection detection = f.detector.detect_in_mask(mask.mask(), region.x, region.y);
    benchmark::DoNotOptimize(detection);
  }
}
BENCHMARK(BM_SquareAfterMask)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc::test

BENCHMARK_MAIN();
