// The search for four Hough peaks forming a square of side d.

#include <gtest/gtest.h>

#include <numbers>

#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/square_search.hpp"

namespace irloc {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// A Hough peak at theta (rad, [0, pi)) and rho (metres).
HoughLine peak(double theta, double rho_metres, std::uint32_t votes) {
  HoughLine line;
  line.theta = theta;
  line.rho = rho_metres * kPlaneUnitsPerMetre;
  line.votes = votes;
  return line;
}

TEST(SquareSearch, FindsTheFourSidesAmongDistractors) {
  HoughLineList peaks;
  peaks.push_back(peak(30 * kDegree, 1.5, 200));     // solid
  peaks.push_back(peak(31 * kDegree, 0.5, 150));     // a 1 m distractor, parallel
  peaks.push_back(peak(120 * kDegree, -0.2, 110));
  peaks.push_back(peak(75 * kDegree, 0.9, 105));     // diagonal clutter
  peaks.push_back(peak(29 * kDegree, -0.45, 100));   // the opposite side, 1.95 m away
  peaks.push_back(peak(121 * kDegree, 1.82, 90));    // the last side, 2.02 m from the third
  SquareCandidates candidates;
  find_square_candidates(peaks, {2.0, 0.1, 10 * kDegree}, candidates);
  ASSERT_EQ(candidates.size(), 1u);
  const SquareSides& sides = candidates[0];
  EXPECT_EQ(sides.votes, 200u + 110 + 100 + 90);
  EXPECT_DOUBLE_EQ(sides.sides[0].rho, 1.5);
  EXPECT_DOUBLE_EQ(sides.sides[2].rho, -0.45);
  EXPECT_DOUBLE_EQ(sides.sides[1].rho, -0.2);
  EXPECT_DOUBLE_EQ(sides.sides[3].rho, 1.82);
}

TEST(SquareSearch, ParallelAcrossTheThetaWrap) {
  // theta 179 deg, rho r is the line theta -1 deg, rho -r: parallel to a line at 1 deg.
  HoughLineList peaks;
  peaks.push_back(peak(1 * kDegree, 1.0, 100));
  peaks.push_back(peak(179 * kDegree, 1.0, 100));  // = (-1 deg, -1.0): 2 m from the first
  peaks.push_back(peak(90 * kDegree, 1.0, 100));
  peaks.push_back(peak(91 * kDegree, -1.0, 100));
  SquareCandidates candidates;
  find_square_candidates(peaks, {2.0, 0.1, 10 * kDegree}, candidates);
  EXPECT_EQ(candidates.size(), 1u);
}

// Whether four of the peaks form a square of side 2 m within the tolerances.
bool forms_square(const HoughLineList& peaks, double angle_tolerance) {
  SquareCandidates candidates;
  find_square_candidates(peaks, {2.0, 0.1, angle_tolerance}, candidates);
  return !candidates.empty();
}

TEST(SquareSearch, RejectsWrongSizeAndWrongAngles) {
  HoughLineList too_big;  // 2.3 m apart: beyond 10 %
  for (const HoughLine& line : {peak(0, 1.15, 100), peak(0, -1.15, 100), peak(90 * kDegree, 1.0, 100),
                                peak(90 * kDegree, -1.0, 100)}) {
    too_big.push_back(line);
  }
  EXPECT_FALSE(forms_square(too_big, 10 * kDegree));
  HoughLineList skewed;  // the pairs meet at 75 degrees
  for (const HoughLine& line : {peak(0, 1.0, 100), peak(0, -1.0, 100), peak(75 * kDegree, 1.0, 100),
                                peak(75 * kDegree, -1.0, 100)}) {
    skewed.push_back(line);
  }
  EXPECT_FALSE(forms_square(skewed, 10 * kDegree));
  EXPECT_TRUE(forms_square(skewed, 16 * kDegree));
  HoughLineList three;  // one side missing
  for (const HoughLine& line : {peak(0, 1.0, 100), peak(0, -1.0, 100), peak(90 * kDegree, 1.0, 100)}) {
    three.push_back(line);
  }
  EXPECT_FALSE(forms_square(three, 10 * kDegree));
}

// Every square hypothesis is kept, strongest first: a stray strip beside a side makes a second set.
TEST(SquareSearch, KeepsEveryHypothesisStrongestFirst) {
  HoughLineList peaks;
  peaks.push_back(peak(0, 1.0, 100));
  peaks.push_back(peak(0, -1.0, 60));   // a dashed side
  peaks.push_back(peak(0, -1.18, 90));  // a strip of tape 0.18 m beyond it: 2.18 m, within 10 %
  peaks.push_back(peak(90 * kDegree, 1.0, 80));
  peaks.push_back(peak(90 * kDegree, -1.0, 70));
  SquareCandidates candidates;
  find_square_candidates(peaks, {2.0, 0.1, 10 * kDegree}, candidates);
  ASSERT_EQ(candidates.size(), 2u);
  EXPECT_EQ(candidates[0].votes, 100u + 90 + 80 + 70);  // the strip outvotes the dashed side
  EXPECT_EQ(candidates[1].votes, 100u + 60 + 80 + 70);
}

}  // namespace
}  // namespace irloc
