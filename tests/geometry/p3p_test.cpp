// P3P on many random problems and on the near-degenerate configurations of the issue.

#include "algo/geometry/p3p.hpp"

#include <gtest/gtest.h>

#include "algo/geometry/pose.hpp"
#include "tests/geometry/p3p_problems.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::P3PProblem;
using test::P3PProblemGenerator;

struct Tally {
  int problems = 0, truth_missing = 0, bad_solutions = 0, solutions = 0;
  double worst_truth_error = 0, worst_bearing_error = 0;
};

// Solves one problem and counts its outcome.
void solve_and_record(const P3PProblem& problem, double truth_tolerance, double bearing_tolerance, Tally& tally) {
  P3PSolutions solutions;
  solve_p3p(problem.world, problem.bearings, solutions);
  ++tally.problems;
  tally.solutions += static_cast<int>(solutions.size());
  double best = 1e300;
  for (const RigidTransform& solution : solutions) {
    best = std::min(best, test::pose_error(problem, solution));
    const double bearing_error = test::worst_bearing_error(problem, solution);
    tally.worst_bearing_error = std::max(tally.worst_bearing_error, bearing_error);
    if (bearing_error > bearing_tolerance || std::abs(solution.rotation.determinant() - 1) > 1e-9) {
      ++tally.bad_solutions;
    }
  }
  if (best < truth_tolerance) {
    tally.worst_truth_error = std::max(tally.worst_truth_error, best);
  } else {
    ++tally.truth_missing;
    std::printf("  truth missing: best error %.3g of %zu solutions\n", best, solutions.size());
  }
}

Tally run(P3PProblemGenerator& generator, int count, double truth_tolerance, double bearing_tolerance) {
  Tally tally;
  for (int n = 0; n < count; ++n) solve_and_record(generator.next(), truth_tolerance, bearing_tolerance, tally);
  return tally;
}

void print(const char* name, const Tally& t) {
  std::printf("%s: %d problems, truth missing %d, bad solutions %d, %.2f solutions each, "
              "worst truth error %.2e, worst bearing error %.2e rad\n",
              name, t.problems, t.truth_missing, t.bad_solutions, double(t.solutions) / t.problems,
              t.worst_truth_error, t.worst_bearing_error);
}

// The acceptance test: 1e5 random problems, the truth among the solutions in >= 99.99 %
// of them, and no solution that does not reproduce its own bearings.
TEST(P3P, HundredThousandRandomProblems) {
  P3PProblemGenerator generator(1);
  const Tally tally = run(generator, 100000, 1e-6, 1e-8);
  print("random", tally);
  EXPECT_LE(tally.truth_missing, 10);
  EXPECT_EQ(tally.bad_solutions, 0);
}

TEST(P3P, PointsCloseTogether) {  // a 2 cm triangle 3 to 5 m away
  P3PProblemGenerator generator(2, 0.003, 3, 5);
  const Tally tally = run(generator, 5000, 1e-4, 1e-8);
  print("close together", tally);
  EXPECT_LE(tally.truth_missing, 5);  // 0.1 %: these problems are ill-conditioned
  EXPECT_EQ(tally.bad_solutions, 0);
}

TEST(P3P, FarAway) {  // a 60 degree view of points 100 to 101 m away
  P3PProblemGenerator generator(3, 0.5, 100, 101);
  const Tally tally = run(generator, 5000, 1e-5, 1e-8);
  print("far away", tally);
  EXPECT_LE(tally.truth_missing, 5);  // 0.1 %: these problems are ill-conditioned
  EXPECT_EQ(tally.bad_solutions, 0);
}

TEST(P3P, NearlyCollinearPoints) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> unit(-1, 1);
  Tally tally;
  for (int n = 0; n < 5000; ++n) {
    // Points on a line, the middle one pushed 1 mm off it, seen from about 2 m.
    P3PProblem problem;
    const Eigen::Vector3d along = Eigen::Vector3d(unit(rng), unit(rng), 0.3 * unit(rng)).normalized();
    const Eigen::Vector3d off = along.cross(Eigen::Vector3d(unit(rng), unit(rng), unit(rng))).normalized();
    problem.world = {-0.5 * along, 0.1 * along + 1e-3 * off, 0.5 * along};
    const RigidTransform world_from_camera{rotation_from_rpy(0.2 * unit(rng), 0.2 * unit(rng), 3 * unit(rng)),
                                           Eigen::Vector3d(unit(rng), unit(rng), -2)};
    problem.camera_from_world = world_from_camera.inverse();
    for (int i = 0; i < 3; ++i) problem.bearings[i] = (problem.camera_from_world * problem.world[i]).normalized();
    solve_and_record(problem, 1e-4, 1e-8, tally);
  }
  print("nearly collinear", tally);
  EXPECT_LE(tally.truth_missing, 5);
  EXPECT_EQ(tally.bad_solutions, 0);
}

TEST(P3P, DegenerateInputGivesNoSolution) {
  P3PSolutions solutions;
  const std::array<Eigen::Vector3d, 3> bearings = {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.1, 0, 1),
                                                   Eigen::Vector3d(0, 0.1, 1)};
  EXPECT_EQ(solve_p3p({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)}, bearings,
                      solutions),
            0);
  EXPECT_EQ(solve_p3p({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)},
                      {bearings[0], bearings[0], bearings[0]}, solutions),
            0);
  EXPECT_EQ(solve_p3p({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)},
                      {bearings[0], Eigen::Vector3d::Zero(), bearings[2]}, solutions),
            0);
  EXPECT_TRUE(solutions.empty());
}

TEST(P3P, AllocatesNothing) {
  P3PProblemGenerator generator(5);
  const P3PProblem problem = generator.next();
  P3PSolutions solutions;
  test::AllocationCounter counter;
  EXPECT_GE(solve_p3p(problem.world, problem.bearings, solutions), 1);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace irloc
