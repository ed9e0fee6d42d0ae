// How far one drive's normalized errors scatter when the sigmas are exact: the survey of the
// synthetic corridor (corridor.hpp: Gaussian centroid noise only, 0.1 px, which the sigmas model)
// driven out, back and out again, sampled every 0.26 m as the goal family's drives are, for
// installation seeds 100 to 100 + N - 1. Per drive the normalized errors' RMS per axis and whether
// all four are within issue 28's 0.5-1.5; at the end, how many were, and the RMS over every drive
// (docs/survey.md, "How far one drive's RMS scatters").
//
//   survey_sigma_spread [N]     (default 40; about 0.1 s of CPU per drive)

#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "tests/survey/corridor_survey.hpp"

int main(int argc, char** argv) {
  using namespace irloc;
  const int drives = argc > 1 ? std::atoi(argv[1]) : 40;
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
    const Eigen::Vector4d rms = one.rms();
    const bool in_band = (rms.array() >= 0.5).all() && (rms.array() <= 1.5).all();
    within += in_band ? 1 : 0;
    std::printf("seed %u: NE rms %.2f %.2f %.2f %.2f%s\n", seed, rms[0], rms[1], rms[2], rms[3], in_band ? "" : "  outside 0.5-1.5");
  }
  const Eigen::Vector4d rms = every.rms();
  std::printf("%d of %d drives within 0.5-1.5 on every axis; over every drive NE rms %.2f %.2f %.2f %.2f (%d markers)\n",
              within, drives, rms[0], rms[1], rms[2], rms[3], every.markers);
  return 0;
}
