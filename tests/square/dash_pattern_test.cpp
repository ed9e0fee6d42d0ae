// Solid and dashed sides told apart by their fill, with parts hidden.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "algo/markers/square/ceiling_plane_map.hpp"
#include "algo/markers/square/corner_order.hpp"
#include "algo/markers/square/dash_pattern.hpp"

namespace irloc::square {
namespace {

// Tape points every `step` metres along a 2 m side from (0, 0) to (2, 0), 5 cm wide, dashed or
// not, with [hide_from, hide_to] hidden.
std::vector<Eigen::Vector2d> side_points(bool dashed, double step, double hide_from = -1, double hide_to = -1) {
  std::vector<Eigen::Vector2d> points;
  for (double s = -0.025; s <= 2.025; s += step) {
    if (s >= hide_from && s <= hide_to) continue;
    const bool corner = s < 0.025 || s > 1.975;
    if (dashed && !corner && std::fmod(s, 0.2) >= 0.1) continue;
    for (double t = -0.02; t <= 0.02; t += step) {
      points.emplace_back(s, t);
    }
  }
  return points;
}

DashPattern measure(const std::vector<Eigen::Vector2d>& points) {
  return measure_dash_pattern(points, {0, 0}, {2, 0}, DashGeometry{});
}

TEST(DashPattern, SolidFillsItsWholeLength) {
  const DashPattern solid = measure(side_points(false, 0.005));
  EXPECT_GT(solid.fill, 0.97);
  EXPECT_GT(solid.visible_fraction, 0.97);
  EXPECT_EQ(solid.gap_rate, 0);
}

TEST(DashPattern, DashedFillsAboutHalf) {
  const DashPattern dashed = measure(side_points(true, 0.005));
  EXPECT_NEAR(dashed.fill, 0.55, 0.2);
  EXPECT_GT(dashed.visible_fraction, 0.97);
  // Nine full gaps in the 1.9 m between the corner patches: 9.5 periods.
  EXPECT_NEAR(dashed.gap_rate, 9 / 9.5, 0.08);
}

TEST(DashPattern, SparselySampledFarSolidTapeStillReadsSolid) {
  // Far tape: a pixel every 3.5 cm along the side.
  const DashPattern solid = measure(side_points(false, 0.035));
  EXPECT_GT(solid.fill, 0.9);
  EXPECT_EQ(solid.gap_rate, 0);
  // Far dashed tape keeps its gaps.
  EXPECT_GT(measure(side_points(true, 0.035)).gap_rate, 0.8);
}

TEST(DashPattern, HalfHiddenSidesKeepTheirKind) {
  const DashPattern solid = measure(side_points(false, 0.005, 0.4, 1.4));
  EXPECT_GT(solid.fill, 0.97);
  EXPECT_NEAR(solid.visible_fraction, 0.5, 0.05);
  EXPECT_EQ(solid.gap_rate, 0);
  const DashPattern dashed = measure(side_points(true, 0.005, 1.0, 2.1));
  EXPECT_NEAR(dashed.fill, 0.55, 0.2);
  EXPECT_NEAR(dashed.visible_fraction, 0.5, 0.06);
  EXPECT_GT(dashed.gap_rate, 0.7);
}

TEST(DashPattern, NothingSeenIsNothingVisible) {
  const DashPattern empty = measure({});
  EXPECT_EQ(empty.visible_fraction, 0);
  EXPECT_EQ(empty.fill, 0);
}

TEST(CornerOrder, SolidSideStartsAtC0InTheMapsTurn) {
  // Measured corners of a square going counter-clockwise; corner k ends side k.
  const std::array<Eigen::Vector2d, 4> measured{Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1),
                                                Eigen::Vector2d(-1, -1)};
  for (int solid = 0; solid < 4; ++solid) {
    const auto start = measured[static_cast<std::size_t>((solid + 3) % 4)];
    const auto end = measured[static_cast<std::size_t>(solid)];
    // Map turning counter-clockwise: c0 -> c1 is the solid side in measured order.
    const auto ccw = order_corners(measured, solid, +1);
    EXPECT_EQ(ccw[0], start);
    EXPECT_EQ(ccw[1], end);
    EXPECT_GT(turn(ccw[0], ccw[1], ccw[2]), 0);
    // Map turning clockwise: the same side, walked the other way.
    const auto cw = order_corners(measured, solid, -1);
    EXPECT_EQ(cw[0], end);
    EXPECT_EQ(cw[1], start);
    EXPECT_LT(turn(cw[0], cw[1], cw[2]), 0);
    EXPECT_LT(turn(cw[1], cw[2], cw[3]), 0);
  }
}

TEST(DashPattern, KeepsThePhaseOfItsOwnPatternOnly) {
  const std::vector<Eigen::Vector2d> dashed = side_points(true, 0.005);
  const DashGeometry own{0.05, 0.10, 0.10};
  // sin(pi / 2) / (pi / 2) for dashes half the period.
  const DashPattern seen = measure_dash_pattern(dashed, {0, 0}, {2, 0}, own);
  EXPECT_NEAR(seen.phase_from_start, 2 / std::numbers::pi, 0.05);
  // Read from the other end (2 m: a whole number of periods) the dashes are out of phase.
  EXPECT_LT(seen.phase_from_end, -0.5);
  EXPECT_NEAR(measure_dash_pattern(dashed, {2, 0}, {0, 0}, own).phase_from_end, 2 / std::numbers::pi, 0.05);
  // Another period, or a solid side: no phase.
  EXPECT_NEAR(measure_dash_pattern(dashed, {0, 0}, {2, 0}, DashGeometry{0.05, 0.20, 0.10}).phase_from_start, 0, 0.1);
  EXPECT_NEAR(measure_dash_pattern(dashed, {0, 0}, {2, 0}, DashGeometry{0.05, 0.30, 0.15}).phase_from_start, 0, 0.1);
  EXPECT_NEAR(measure(side_points(false, 0.005)).phase_from_start, 0, 0.05);
  // Far solid tape with sampling holes: a few gaps, still no phase.
  std::vector<Eigen::Vector2d> holed;
  for (const Eigen::Vector2d& p : side_points(false, 0.01)) {
    if (std::fmod(p.x() + 2.0, 0.37) > 0.05) holed.push_back(p);
  }
  EXPECT_NEAR(measure(holed).phase_from_start, 0, 0.1);
  // Half hidden: the phase of what is seen still holds.
  EXPECT_NEAR(measure(side_points(true, 0.005, 0.5, 1.5)).phase_from_start, 2 / std::numbers::pi, 0.05);
}

}  // namespace
}  // namespace irloc::square
