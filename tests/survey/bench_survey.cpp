// Incremental cost of the survey per frame: SurveyEstimator::observe on the corridor (12 markers,
// 2-4 in view, 0.1 px noise) after one pass, for graph capacities of 16 and 64 markers (the
// dense normal equations are sized by the capacity). And the bound by map size (issue 32): a map
// of all 4,096 IDs (the corridor among 4,084 markers no drive sees) at start-up (time and heap),
// per frame, and per map write (estimated_map).

#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "tests/support/heap_in_use.hpp"
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

// Start-up of a survey of the 4,096-marker map with the default capacity (max_markers 64).
void BM_survey_startup_every_id(benchmark::State& state) {
  const MarkerMap map = test::with_every_other_id(test::Corridor(5).drawing);
  std::size_t heap = 0;
  for (auto _ : state) {
    const std::size_t before = test::heap_in_use();
    survey::SurveyEstimator survey(test::corridor_camera(), test::corridor_mount(), map, survey::SurveyConfig{});
    heap = test::heap_in_use() - before;
    benchmark::DoNotOptimize(survey);
  }
  state.counters["markers"] = static_cast<double>(map.dot_markers.size());
  state.counters["heap_MB"] = static_cast<double>(heap) / 1e6;
}
BENCHMARK(BM_survey_startup_every_id)->Unit(benchmark::kMillisecond);

// Per frame and per map write on the 4,096-marker map, after one pass along the corridor.
struct EveryIdSurvey {
  test::Corridor corridor{5};
  survey::SurveyEstimator survey{test::corridor_camera(), test::corridor_mount(), test::with_every_other_id(corridor.drawing),
                                 survey::SurveyConfig{}};
  std::vector<PointObservationList> frames;
  EveryIdSurvey() {
    std::mt19937 random(1);
    for (const test::PassPose& pose : test::corridor_pass(9.6, false)) {
      frames.push_back(test::observe(corridor.truth.dot_markers, pose.x, pose.y, pose.yaw, 0.1, random));
    }
    for (const PointObservationList& frame : frames) survey.observe(frame);
  }
};

void BM_survey_observe_every_id(benchmark::State& state) {
  EveryIdSurvey run;
  std::size_t i = 0;
  for (auto _ : state) {
    run.survey.observe(run.frames[i]);
    i = (i + 1) % run.frames.size();
  }
}
BENCHMARK(BM_survey_observe_every_id)->Unit(benchmark::kMicrosecond);

void BM_survey_map_write_every_id(benchmark::State& state) {
  EveryIdSurvey run;
  for (auto _ : state) {
    const MarkerMap map = run.survey.estimated_map();
    benchmark::DoNotOptimize(map);
  }
}
BENCHMARK(BM_survey_map_write_every_id)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace irloc

BENCHMARK_MAIN();
