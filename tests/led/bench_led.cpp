// Per-frame time of the LED landmark source on the goal scene (640 x 480, five LEDs on a wall
// 4 m ahead, dof 6): detection alone, a whole attempt that searches the association (start-up or
// lost track), and a whole attempt that tracks from the last pose (the steady state).

#include <benchmark/benchmark.h>

#include "algo/markers/led/led_landmark_source.hpp"
#include "tests/led/led_scene.hpp"

namespace irloc::led {
namespace {

struct Fixture {
  test::LedScene scene;
  test::RenderedPair pair;
  MarkerMap map;

  Fixture() {
    scene.scene_leds = {test::led_at(4.0, -1.2, 0.9), test::led_at(4.0, -0.4, 1.4), test::led_at(4.0, 0.5, 0.7),
                        test::led_at(4.0, 1.3, 1.2), test::led_at(4.0, 0.1, 1.7)};
    scene.base_xyz = {0.3, -0.2, 0.02};
    scene.yaw = 0.06;
    scene.roll = 0.03;
    scene.pitch = -0.04;
    test::render_pair(scene, pair);
    map.led_landmarks = scene.scene_leds;
  }
  SourceSetup setup() const { return {scene.camera, scene.mount, Dof::full6, map}; }
};

Fixture& fixture() {
  static Fixture instance;
  return instance;
}

void BM_LedDetect(benchmark::State& state) {
  Fixture& f = fixture();
  LedDetector detector(640, 480, 8, LedSourceConfig{});
  LedDetectionList detections;
  LedDetectionCounters counters;
  for (auto _ : state) {
    detector.detect(f.pair.on.image, &f.pair.off.image, detections, counters);
    benchmark::DoNotOptimize(detections);
  }
  if (detections.size() != 5) state.SkipWithError("expected 5 LEDs");
}
BENCHMARK(BM_LedDetect)->Unit(benchmark::kMillisecond);

// Every attempt searches: the track is dropped as too old.
void BM_LedAttemptSearch(benchmark::State& state) {
  Fixture& f = fixture();
  LedSourceConfig config;
  config.track_timeout = 0;
  LedLandmarkSource source(f.setup(), config);
  SourceResult result;
  Frame on = f.pair.on;
  for (auto _ : state) {
    on.t_ns += 66'666'667;
    source.process(SourceInput{on, &f.pair.off}, result);
    benchmark::DoNotOptimize(result);
  }
  if (!result.ok || source.last_hypotheses() == 0) state.SkipWithError("expected a searched pose");
}
BENCHMARK(BM_LedAttemptSearch)->Unit(benchmark::kMillisecond);

void BM_LedAttemptTrack(benchmark::State& state) {
  Fixture& f = fixture();
  LedLandmarkSource source(f.setup(), LedSourceConfig{});
  SourceResult result;
  Frame on = f.pair.on;
  source.process(SourceInput{on, &f.pair.off}, result);  // the search that starts the track
  for (auto _ : state) {
    on.t_ns += 66'666'667;
    source.process(SourceInput{on, &f.pair.off}, result);
    benchmark::DoNotOptimize(result);
  }
  if (!result.ok || source.last_hypotheses() != 0) state.SkipWithError("expected a tracked pose");
}
BENCHMARK(BM_LedAttemptTrack)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc::led
BENCHMARK_MAIN();
