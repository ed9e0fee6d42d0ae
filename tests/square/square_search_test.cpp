// The search for four Hough peaks forming a square of side d.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/square_search.hpp"

#include <Eigen/Geometry>

namespace irloc::square {
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

// Plane points every 2.5 cm along the segment from a to b (metres), two rows 2.5 cm apart (a
// 5 cm tape on the thinning grid); dashed: 0.1 m on, 0.1 m off.
void add_tape(std::vector<PlanePoint>& points, Eigen::Vector2d a, Eigen::Vector2d b, bool dashed) {
  const double length = (b - a).norm();
  const Eigen::Vector2d along = (b - a) / length, across(-along.y(), along.x());
  for (double s = 0; s <= length; s += 0.025) {
    if (dashed && std::fmod(s, 0.2) >= 0.1) continue;
    for (const double t : {-0.0125, 0.0125}) {
      const Eigen::Vector2d p = a + s * along + t * across;
      points.push_back({static_cast<std::int32_t>(std::lround(p.x() * kPlaneRawPerMetre)),
                        static_cast<std::int32_t>(std::lround(p.y() * kPlaneRawPerMetre))});
    }
  }
}

HoughConfig plane_hough() {
  HoughConfig config;
  config.rho_resolution = static_cast<std::int32_t>(0.05 * kPlaneRawPerMetre);
  config.rho_max = static_cast<std::int32_t>(6 * kPlaneRawPerMetre);
  config.min_votes = 8;
  config.nms_rho = 2;
  config.nms_theta = 3;
  config.inlier_distance = static_cast<std::int32_t>(0.025 * kPlaneRawPerMetre);
  return config;
}

// Whether the hypothesis has a side on the line of normal angle theta (mod pi) and rho (metres).
bool has_side(const SquareSides& sides, double theta, double rho) {
  for (const PlaneLine& line : sides.sides) {
    const double turn = std::remainder(line.theta - theta, 2 * std::numbers::pi);
    if (std::abs(turn) < 1.5 * kDegree && std::abs(line.rho - rho) < 0.05) return true;
    if (std::abs(std::abs(turn) - std::numbers::pi) < 1.5 * kDegree && std::abs(line.rho + rho) < 0.05) return true;
  }
  return false;
}

// A long strip of safety tape 0.18 m beside a dashed side outvotes it, and its side lobes hide
// the side from the peaks' non-maximum suppression: the peaks form no square with that side. The
// level search reads the accumulator's columns at the square's orientation and finds it. (The
// camera is at the origin; the square at three places off it, at three headings.)
TEST(SquareSearch, LevelSearchFindsASideBesideAStrongerStrip) {
  for (const Eigen::Vector2d& centre : {Eigen::Vector2d(-1.5, 1.5), Eigen::Vector2d(0, -1.5), Eigen::Vector2d(1.5, -1.5)}) {
    for (const double yaw : {0.0, 20 * kDegree, 40 * kDegree}) {
      const Eigen::Rotation2Dd r(yaw);
      const auto at = [&](double x, double y) { return Eigen::Vector2d(centre + r * Eigen::Vector2d(x, y)); };
      std::vector<PlanePoint> points;
      add_tape(points, at(-1, -1), at(1, -1), false);  // solid
      add_tape(points, at(1, -1), at(1, 1), true);
      add_tape(points, at(1, 1), at(-1, 1), true);
      add_tape(points, at(-1, 1), at(-1, -1), true);
      add_tape(points, at(-1.18, -1.3), at(-1.18, 1.3), false);  // the strip, 2.6 m long
      HoughLines hough(plane_hough());
      HoughLineList peaks;
      hough.detect(points, peaks);
      const SquareSearchParams params{2.0, 0.1, 10 * kDegree};
      // The side x = -1 and its opposite x = +1, in the square's frame.
      const Eigen::Vector2d normal = r * Eigen::Vector2d(-1, 0);
      const double theta = std::atan2(normal.y(), normal.x());
      const double rho = normal.dot(at(-1, 0));
      const auto has_both = [&](const SquareSides& sides) {
        return has_side(sides, theta, rho) && has_side(sides, theta + std::numbers::pi, 2.0 - rho);
      };
      SquareCandidates from_peaks;
      find_square_candidates(peaks, params, from_peaks);
      EXPECT_FALSE(std::any_of(from_peaks.begin(), from_peaks.end(), has_both)) << centre.transpose() << " " << yaw;
      SquareCandidates level;
      find_level_square_candidates(hough, peaks, params, level);
      EXPECT_TRUE(std::any_of(level.begin(), level.end(), has_both)) << centre.transpose() << " " << yaw;
    }
  }
}

}  // namespace
}  // namespace irloc::square
