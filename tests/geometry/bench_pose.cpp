// Cost of one estimate_pose call, the per-marker work of the dot and square paths: a 16-dot
// marker and a 4-corner square seen by an upward camera with 0.5 px noise, under each dof.

#include <vector>

#include <benchmark/benchmark.h>

#include "algo/geometry/pose_solver.hpp"
#include "tests/geometry/calibrations.hpp"
#include "tests/geometry/ceiling_scene.hpp"

namespace irloc {
namespace {

void BM_estimate_pose(benchmark::State& state, bool square, Dof dof) {
  const CameraModel camera(test::plumb_bob_lens());
  const std::vector<Eigen::Vector3d> points = square ? test::square(0.2, -0.1, 0.3) : test::dot_grid(0.2, -0.1, 1.0);
  const RigidTransform truth{rotation_from_rpy(0, 0, 0.4), Eigen::Vector3d(0.5, 0.3, 0)};
  std::mt19937 rng(1);
  std::vector<std::vector<Eigen::Vector2d>> observations(64);
  for (auto& pixels : observations) test::observe(points, camera, truth, test::up_mount(), 0.5, rng, pixels);
  RefinementOptions options;
  options.dof = dof;
  std::size_t i = 0;
  int failures = 0;
  for (auto _ : state) {
    const PoseFit fit = estimate_pose(points, observations[i], camera, test::up_mount(), options);
    failures += fit.ok ? 0 : 1;
    benchmark::DoNotOptimize(fit);
    i = (i + 1) % observations.size();
  }
  state.counters["failures"] = failures;
}

BENCHMARK_CAPTURE(BM_estimate_pose, dots16_dof3, false, Dof::planar3);
BENCHMARK_CAPTURE(BM_estimate_pose, dots16_dof4, false, Dof::height4);
BENCHMARK_CAPTURE(BM_estimate_pose, dots16_dof6, false, Dof::full6);
BENCHMARK_CAPTURE(BM_estimate_pose, square4_dof3, true, Dof::planar3);
BENCHMARK_CAPTURE(BM_estimate_pose, square4_dof6, true, Dof::full6);

}  // namespace
}  // namespace irloc

BENCHMARK_MAIN();
