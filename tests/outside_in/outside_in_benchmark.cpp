// Per-frame time of the outside-in source at 640 x 480 (the goal's webcam), with the robot
// tracked at about 4 m and a person in view: the whole process() call, stage times in the
// result. The two frames alternate, so the robot steps back and forth by 5 cm.
#include <benchmark/benchmark.h>

#include "tests/outside_in/outside_in_drive.hpp"

namespace irloc::test {
namespace {

SceneState bench_scene(int i) {
  SceneState scene;
  scene.robot = FloorPose{2.5 + 0.05 * i, 0.2, 0.0};
  if (i > 30) scene.person = Person{Eigen::Vector2d(3.0, 1.5)};
  return scene;
}

void BM_OutsideInFrame(benchmark::State& state) {
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera);
  renderer.auto_exposure = false;
  // Start with the robot out of the way, then drive it in so that it is tracked.
  std::vector<std::uint8_t> frames[2];
  SourceResult result;
  for (int i = 0; i < 40; ++i) {
    FrameTruth truth;
    SceneState scene = bench_scene(i);
    if (i < 5) scene.robot.reset();
    const auto& pixels = renderer.render(scene, truth);
    if (i >= 38) frames[i - 38] = pixels;
    rig.source->process({Frame{std::uint64_t(i), std::int64_t(i) * 100'000'000, false, ImageView8(pixels.data(), 640, 480)},
                         nullptr},
                        result);
  }
  int i = 40, poses = 0;
  for (auto _ : state) {
    const Frame frame{std::uint64_t(i), std::int64_t(i) * 100'000'000, false, ImageView8(frames[i % 2].data(), 640, 480)};
    rig.source->process({frame, nullptr}, result);
    poses += result.ok;
    ++i;
  }
  state.counters["pose_rate"] = benchmark::Counter(double(poses) / std::max<double>(state.iterations(), 1));
}
BENCHMARK(BM_OutsideInFrame)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc::test

BENCHMARK_MAIN();
