// Per-frame costs of the robot side: the strobe brightness check on the boards' image sizes, and
// encoding one pose attempt in each serial protocol. `make bench` writes build/bench/hw.json.

#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "firmware/protocol/stargazer_pose_stream.hpp"
#include "firmware/strobe_check.hpp"

namespace irloc::firmware {
namespace {

void strobe_check(benchmark::State& state) {
  const int width = static_cast<int>(state.range(0));
  const int height = static_cast<int>(state.range(1));
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<std::uint8_t> lit(pixels), dark(pixels);
  for (std::size_t i = 0; i < pixels; ++i) {
    dark[i] = static_cast<std::uint8_t>(20 + i % 7);
    lit[i] = static_cast<std::uint8_t>(i % 997 < 9 ? 200 : dark[i]);
  }
  Frame on, off;
  on.image = ImageView8(lit.data(), width, height, width);
  off.image = ImageView8(dark.data(), width, height, width);
  for (auto _ : state) benchmark::DoNotOptimize(check_strobe_pair(on, off, {}));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pixels));
}
BENCHMARK(strobe_check)->Args({820, 616})->Args({1456, 1088})->Args({640, 480})->Unit(benchmark::kMicrosecond);

PoseEstimate pose_at(std::int64_t t_ns) {
  PoseEstimate pose;
  pose.ok = true;
  pose.t_ns = t_ns;
  pose.x = 1.25;
  pose.y = -3.5;
  pose.yaw = 0.7;
  pose.confidence = 0.8;
  pose.marker_id = 1782;
  return pose;
}

void mavlink_encode(benchmark::State& state) {
  MavlinkPoseStream stream({});
  std::int64_t t_ns = 0;
  for (auto _ : state) benchmark::DoNotOptimize(stream.encode(pose_at(t_ns += 33'000'000)).size());
}
BENCHMARK(mavlink_encode);

void stargazer_encode(benchmark::State& state) {
  MarkerMap map;
  map.dot_markers.push_back(DotMarker{1782, {1.0, 2.0, 2.6}});
  StarGazerPoseStream stream(map, 0.3);
  for (auto _ : state) benchmark::DoNotOptimize(stream.encode(pose_at(0)).size());
}
BENCHMARK(stargazer_encode);

}  // namespace
}  // namespace irloc::firmware

BENCHMARK_MAIN();
