// Incremental cost of the survey per frame: SurveyEstimator::observe on the corridor (12 markers,
// 2-4 in view, 0.1 px noise) after one pass, for graph capacities of 16 and 64 markers (the
// dense normal equations are sized by the capacity).

#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "tests/survey/corridor_survey.hpp"

namespace irloc {
namespace {

void BM_survey_observe(benchmark::State& state) {
  const test::Corridor corridor(5);
  survey::SurveyEstimator survey = test::corridor_survey(corridor.drawing, static_cast<std::size_t>(state.range(0)));
  std::mt19937 random(1);
  std::vector<PointObservationList> frames;
  for (const test::PassPose& pose : test::corridor_pass(9.6, false)) {
    frames.push_back(test::observe(corridor.truth.dot_markers, pose.x, pose.y, pose.yaw, 0.1, random));
  }
  for (const PointObservationList& frame : frames) survey.observe(frame);  // one pass first
  std::size_t i = 0;
  for (auto _ : state) {
    survey.observe(frames[i]);
    i = (i + 1) % frames.size();
  }
  state.counters["markers_in_graph"] = static_cast<double>(corridor.drawing.dot_markers.size());
}

BENCHMARK(BM_survey_observe)->Arg(16)->Arg(64)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace irloc

BENCHMARK_MAIN();
