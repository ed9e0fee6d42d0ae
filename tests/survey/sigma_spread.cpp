// How far one drive's normalized errors scatter when the sigmas are exact: the survey of the
// synthetic corridor (corridor.hpp: Gaussian centroid noise only, 0.1 px, which the sigmas model)
// driven out, back and out again, sampled every 0.26 m as the goal family's drives are, for
// installation seeds 100 to 100 + N - 1. Per drive the normalized errors' RMS per axis and whether
// all four are within issue 28's 0.5-1.5; at the end, how many were, and the RMS over every drive
// (docs/survey.md, "How far one drive's RMS scatters"). With G, the drives in consecutive groups
// of G, each group's RMS with its 95 % interval over its drives as survey_goal gives a class's
// over its scenes (scene_interval.hpp), and per axis how many groups' intervals hold 1: how often
// that interval misses where the sigmas are right.
//
//   survey_sigma_spread [N [G]]     (N default 40; about 0.1 s of CPU per drive)

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "tests/survey/corridor_survey.hpp"
#include "tests/survey/scene_interval.hpp"

namespace {

void report_groups(const std::vector<irloc::test::SceneSquares>& drives, std::size_t group) {
  std::array<int, 4> holding{};
  int groups = 0;
  for (std::size_t first = 0; first + group <= drives.size(); first += group, ++groups) {
    const std::vector<irloc::test::SceneSquares> members(drives.begin() + static_cast<std::ptrdiff_t>(first),
                                                         drives.begin() + static_cast<std::ptrdiff_t>(first + group));
    const irloc::test::PooledRms pooled = irloc::test::pooled_rms_over_scenes(members);
    for (std::size_t axis = 0; axis < 4; ++axis) holding[axis] += pooled.interval_includes_one(axis) ? 1 : 0;
    std::printf("drives %zu-%zu: NE rms %.2f [%.2f-%.2f] %.2f [%.2f-%.2f] %.2f [%.2f-%.2f] %.2f [%.2f-%.2f]\n", first,
                first + group - 1, pooled.rms[0], pooled.low[0], pooled.high[0], pooled.rms[1], pooled.low[1],
                pooled.high[1], pooled.rms[2], pooled.low[2], pooled.high[2], pooled.rms[3], pooled.low[3], pooled.high[3]);
  }
  std::printf("groups of %zu drives whose interval holds 1 (x, y, z, yaw): %d %d %d %d of %d\n", group, holding[0],
              holding[1], holding[2], holding[3], groups);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace irloc;
  const int drives = argc > 1 ? std::atoi(argv[1]) : 40;
  const int group = argc > 2 ? std::atoi(argv[2]) : 0;
  std::vector<test::SceneSquares> per_drive;
  constexpr double kPixelNoise = 0.1;  // px
  constexpr std::size_t kEvery = 13;   // of the 2 cm steps: 0.26 m
  test::NormalizedErrors every;
  int within = 0;
  for (int k = 0; k < drives; ++k) {
    const auto seed = static_cast<unsigned>(100 + k);
    const test::Corridor corridor(seed);
    survey::SurveyEstimator survey = test::corridor_survey(corridor.drawing);
    std::mt19937 random(seed);
    for (int pass = 0; pass < 3; ++pass) {
      const std::vector<test::PassPose> poses = test::corridor_pass(9.6, pass % 2 == 1);
      for (std::size_t i = 0; i < poses.size(); i += kEvery) {
        survey.observe(test::observe(corridor.truth.dot_markers, poses[i].x, poses[i].y, poses[i].yaw, kPixelNoise, random));
      }
    }
    test::NormalizedErrors one;
    one.add(survey.estimated_map(), corridor.truth);
    every.add(survey.estimated_map(), corridor.truth);
    per_drive.push_back({{one.squares[0], one.squares[1], one.squares[2], one.squares[3]}, one.markers});
    const Eigen::Vector4d rms = one.rms();
    const bool in_band = (rms.array() >= 0.5).all() && (rms.array() <= 1.5).all();
    within += in_band ? 1 : 0;
    std::printf("seed %u: NE rms %.2f %.2f %.2f %.2f%s\n", seed, rms[0], rms[1], rms[2], rms[3], in_band ? "" : "  outside 0.5-1.5");
  }
  const Eigen::Vector4d rms = every.rms();
  std::printf("%d of %d drives within 0.5-1.5 on every axis; over every drive NE rms %.2f %.2f %.2f %.2f (%d markers)\n",
              within, drives, rms[0], rms[1], rms[2], rms[3], every.markers);
  if (group > 1) report_groups(per_drive, static_cast<std::size_t>(group));
  return 0;
}
