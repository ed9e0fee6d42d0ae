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
  SquareSides sides;
  ASSERT_TRUE(find_square_sides(peaks, {2.0, 0.1, 10 * kDegree}, sides));
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
  SquareSides sides;
  EXPECT_TRUE(find_square_sides(peaks, {2.0, 0.1, 10 * kDegree}, sides));
}

TEST(SquareSearch, RejectsWrongSizeAndWrongAngles) {
  SquareSides sides;
  HoughLineList too_big;  // 2.3 m apart: beyond 10 %
  for (const HoughLine& line : {peak(0, 1.15, 100), peak(0, -1.15, 100), peak(90 * kDegree, 1.0, 100),
                                peak(90 * kDegree, -1.0, 100)}) {
    too_big.push_back(line);
  }
  EXPECT_FALSE(find_square_sides(too_big, {2.0, 0.1, 10 * kDegree}, sides));
  HoughLineList skewed;  // the pairs meet at 75 degrees
  for (const HoughLine& line : {peak(0, 1.0, 100), peak(0, -1.0, 100), peak(75 * kDegree, 1.0, 100),
                                peak(75 * kDegree, -1.0, 100)}) {
    skewed.push_back(line);
  }
  EXPECT_FALSE(find_square_sides(skewed, {2.0, 0.1, 10 * kDegree}, sides));
  EXPECT_TRUE(find_square_sides(skewed, {2.0, 0.1, 16 * kDegree}, sides));
  HoughLineList three;  // one side missing
  for (const HoughLine& line : {peak(0, 1.0, 100), peak(0, -1.0, 100), peak(90 * kDegree, 1.0, 100)}) {
    three.push_back(line);
  }
  EXPECT_FALSE(find_square_sides(three, {2.0, 0.1, 10 * kDegree}, sides));
}

}  // namespace
}  // namespace irloc
