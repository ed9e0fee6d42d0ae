// Rendering speed of the default scenario (640 x 480, 3 x 3 rays per pixel): the goal is
// a 200-frame scene in under 30 s on 2 cores, i.e. under 150 ms per frame with both cores.

#include <benchmark/benchmark.h>

#include "algo/geometry/camera_model.hpp"
#include "host_sim/scenario/default_scenario.hpp"
#include "host_sim/render/noise.hpp"
#include "host_sim/render/renderer.hpp"

namespace irloc::sim {
namespace {

// One LED-on and one LED-off frame: scene radiance and the sensor, as render_dataset does.
void BM_RenderDefaultScenarioStrobePair(benchmark::State& state) {
  const Scenario scenario = parse_scenario(std::string(default_scenario_yaml()), "default");
  const CameraModel camera(scenario.camera.intrinsics);
  const Renderer renderer(scenario, camera);
  const Sensor sensor(scenario.camera, scenario.seed);
  std::vector<float> radiance(static_cast<std::size_t>(renderer.width() * renderer.height()));
  std::vector<std::uint8_t> image(radiance.size());
  double t = 0;
  for (auto _ : state) {
    for (const bool led_on : {true, false}) {
      renderer.render(t, led_on, radiance);
      for_each_row(renderer.height(), [&](int y) {
        const std::size_t offset = static_cast<std::size_t>(y * renderer.width());
        sensor.expose_row(std::span<const float>(&radiance[offset], static_cast<std::size_t>(renderer.width())), 0, y,
                          &image[offset]);
      });
      t += 1 / scenario.camera.frame_rate;
    }
    benchmark::DoNotOptimize(image.data());
  }
  state.counters["frames_per_s"] = benchmark::Counter(2.0 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderDefaultScenarioStrobePair)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace irloc::sim

BENCHMARK_MAIN();
