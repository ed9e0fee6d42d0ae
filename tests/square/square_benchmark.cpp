// Per-frame time of the square path at the goal's 1280 x 1024 (goal: 1 ms), whole and by stage,
// on a ray-cast equisolid frame pair with the robot 1.5 m off the square's centre; and the whole
// path for a tilting robot (dof 6: the robot also rolled 3 and pitched -2 degrees).

#include <benchmark/benchmark.h>

#include <numbers>

#include "algo/markers/square/square_detector.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {
namespace {

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

void BM_SquareDetectTilted(benchmark::State& state) {
  Fixture& f = tilted_fixture();
  for (auto _ : state) {
    SquareDetection detection = f.detector.detect(ImageView8(f.on.view()), ImageView8(f.off.view()), f.noise);
    benchmark::DoNotOptimize(detection);
    if (!detection.found()) state.SkipWithError("tilted square not found");
  }
}
BENCHMARK(BM_SquareDetectTilted)->Unit(benchmark::kMillisecond);

void BM_SquareDetect(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state) {
    SquareDetection detection = f.detector.detect(ImageView8(f.on.view()), ImageView8(f.off.view()), f.noise);
    benchmark::DoNotOptimize(detection);
    if (!detection.found()) state.SkipWithError("square not found");
  }
}
BENCHMARK(BM_SquareDetect)->Unit(benchmark::kMillisecond);

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
