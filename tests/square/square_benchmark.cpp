// Per-frame time of the square path at the goal's 1280 x 1024 (goal: under 5 ms), whole and by
// stage, on a ray-cast equisolid frame pair with the robot 1.5 m off the square's centre.

#include <benchmark/benchmark.h>

#include "algo/markers/square/square_detector.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {
namespace {

struct Fixture {
  TapeScene scene;
  Image8 on, off;
  SquareDetector detector;
  DifferenceNoise noise;         // the pair's shared estimate
  std::uint16_t threshold = 0;   // the tape threshold the detector derives from it

  Fixture()
      : scene(make_scene()),
        detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{}) {
    scene.render(on, off);
    noise = shared_noise(ImageView8(on.view()), ImageView8(off.view()));
    threshold = detector.detect(ImageView8(on.view()), ImageView8(off.view()), noise).threshold;
  }
  static TapeScene make_scene() {
    TapeScene scene;
    scene.camera = fisheye(1280, 1024);
    scene.samples = 2;
    scene.x = 1.2;
    scene.y = -0.9;
    scene.yaw = 0.6;
    return scene;
  }
};

Fixture& fixture() {
  static Fixture instance;
  return instance;
}

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
    benchmark::DoNotOptimize(mask.mask().data());
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
