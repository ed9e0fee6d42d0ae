// P3P speed and reliability: our Lambda Twist solver against OpenCV's solveP3P (P3P, AP3P) on
// the same random problems. Each iteration times one solve; the counters come from a separate,
// untimed pass over every problem:
//   failures        problems whose true pose is not among the solutions (pose error < 1e-6)
//   failures_1e-3   the same with a loose tolerance (pose error < 1e-3)
//   wrong_solutions solutions that do not reproduce their own bearings (error > 1e-6 rad)

#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/calib3d.hpp>

#include "algo/geometry/p3p.hpp"
#include "tests/geometry/p3p_problems.hpp"

namespace irloc {
namespace {

constexpr int kProblems = 10000;
constexpr double kTruthTolerance = 1e-6;  // rotation (Frobenius) + translation / scene distance
constexpr double kLooseTruthTolerance = 1e-3;
constexpr double kBearingTolerance = 1e-6;

// Problem sets: `wide` as in the tests (60 degree cone, depths 0.5-10 m); `marker` like a dot
// marker on the ceiling (three dots of a 12 cm marker 2.5-3 m away: a 1.4 degree cone).
enum class ProblemSet { wide, marker };

const std::vector<test::P3PProblem>& problems(ProblemSet set) {
  auto make = [](test::P3PProblemGenerator generator) {
    std::vector<test::P3PProblem> list;
    for (int i = 0; i < kProblems; ++i) list.push_back(generator.next());
    return list;
  };
  static const std::vector<test::P3PProblem> wide = make(test::P3PProblemGenerator(2024));
  static const std::vector<test::P3PProblem> marker = make(test::P3PProblemGenerator(2025, 0.024, 2.5, 3.0));
  return set == ProblemSet::wide ? wide : marker;
}

template <typename Solver>
void count_outcomes(benchmark::State& state, ProblemSet set, Solver solve) {
  P3PSolutions solutions;
  int failures = 0, loose_failures = 0, wrong = 0, total = 0;
  for (const test::P3PProblem& problem : problems(set)) {
    solve(problem, solutions);
    failures += test::contains_truth(problem, solutions, kTruthTolerance) ? 0 : 1;
    loose_failures += test::contains_truth(problem, solutions, kLooseTruthTolerance) ? 0 : 1;
    for (const RigidTransform& solution : solutions) {
      wrong += test::worst_bearing_error(problem, solution) > kBearingTolerance ? 1 : 0;
    }
    total += static_cast<int>(solutions.size());
  }
  state.counters["problems"] = kProblems;
  state.counters["failures"] = failures;
  state.counters["failures_1e-3"] = loose_failures;
  state.counters["wrong_solutions"] = wrong;
  state.counters["solutions_per_problem"] = double(total) / kProblems;
}

template <typename Solver>
void time_solves(benchmark::State& state, ProblemSet set, Solver solve) {
  const std::vector<test::P3PProblem>& list = problems(set);
  P3PSolutions solutions;
  std::size_t i = 0;
  for (auto _ : state) {
    solve(list[i], solutions);
    benchmark::DoNotOptimize(solutions);
    i = (i + 1) % list.size();
  }
  state.SetItemsProcessed(state.iterations());
  count_outcomes(state, set, solve);
}

void lambda_twist(const test::P3PProblem& problem, P3PSolutions& solutions) {
  solve_p3p(problem.world, problem.bearings, solutions);
}

// OpenCV on normalized image points (identity camera matrix, no distortion).
template <int Flag>
void opencv_p3p(const test::P3PProblem& problem, P3PSolutions& solutions) {
  cv::Matx<double, 3, 3> object;
  cv::Matx<double, 3, 2> image;
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) object(i, k) = problem.world[i](k);
    image(i, 0) = problem.bearings[i].x() / problem.bearings[i].z();
    image(i, 1) = problem.bearings[i].y() / problem.bearings[i].z();
  }
  std::vector<cv::Mat> rvecs, tvecs;
  const int count = cv::solveP3P(cv::Mat(object), cv::Mat(image), cv::Matx33d::eye(), cv::noArray(), rvecs,
                                 tvecs, Flag);
  solutions.clear();
  for (int s = 0; s < count; ++s) {
    cv::Matx33d rotation;
    cv::Rodrigues(rvecs[s], rotation);
    RigidTransform pose;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) pose.rotation(r, c) = rotation(r, c);
      pose.translation(r) = tvecs[s].at<double>(r);
    }
    solutions.push_back(pose);
  }
}

void BM_p3p_lambda_twist(benchmark::State& state, ProblemSet set) { time_solves(state, set, lambda_twist); }
void BM_p3p_opencv_P3P(benchmark::State& state, ProblemSet set) {
  time_solves(state, set, opencv_p3p<cv::SOLVEPNP_P3P>);
}
void BM_p3p_opencv_AP3P(benchmark::State& state, ProblemSet set) {
  time_solves(state, set, opencv_p3p<cv::SOLVEPNP_AP3P>);
}

BENCHMARK_CAPTURE(BM_p3p_lambda_twist, wide, ProblemSet::wide);
BENCHMARK_CAPTURE(BM_p3p_opencv_P3P, wide, ProblemSet::wide);
BENCHMARK_CAPTURE(BM_p3p_opencv_AP3P, wide, ProblemSet::wide);
BENCHMARK_CAPTURE(BM_p3p_lambda_twist, marker, ProblemSet::marker);
BENCHMARK_CAPTURE(BM_p3p_opencv_P3P, marker, ProblemSet::marker);
BENCHMARK_CAPTURE(BM_p3p_opencv_AP3P, marker, ProblemSet::marker);

}  // namespace
}  // namespace irloc

BENCHMARK_MAIN();
