// Per-frame costs of the robot side: encoding one pose attempt in each serial protocol (the strobe
// brightness check is part of the front end: bench_kernels). `make bench` writes build/bench/hw.json.

#include <cstdint>

#include <benchmark/benchmark.h>

#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "firmware/protocol/stargazer_pose_stream.hpp"

namespace irloc::firmware {
namespace {

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
  StarGazerPoseStream stream(map, 0.3, "irloc bench", 115200);
  for (auto _ : state) benchmark::DoNotOptimize(stream.encode(pose_at(0)).size());
}
BENCHMARK(stargazer_encode);

}  // namespace
}  // namespace irloc::firmware

BENCHMARK_MAIN();
