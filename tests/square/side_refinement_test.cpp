// SquareRefiner against a plain reference (the points of each side selected as documented, the
// line through them by an eigen-decomposition of their scatter) and the truth: tape of a 2 m
// square with noise, a strip of clutter beside one side and a lamp of scattered points inside;
// coarse sides off by up to a few centimetres and a few degrees, and one far off.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "algo/markers/square/side_refinement.hpp"

namespace irloc::square {
namespace {

constexpr double kTape = 0.05;

// The reference: each pass, each side by total least squares on the points within kTape of its
// line (3/4 of it in the last pass) and kTape inside both neighbours, among those within
// kGatherWidths tape widths of its coarse line; every stride-th of these in the wide passes.
bool reference_refine(const std::vector<Eigen::Vector2d>& points, const SquareSides& coarse, int passes,
                      std::array<Eigen::Vector2d, 4>& corners) {
  const auto normal = [](const PlaneLine& l) { return Eigen::Vector2d(std::cos(l.theta), std::sin(l.theta)); };
  const auto distance = [&](const PlaneLine& l, const Eigen::Vector2d& p) { return normal(l).dot(p) - l.rho; };
  std::array<std::vector<Eigen::Vector2d>, 4> near, sampled;
  std::array<std::size_t, 4> sampled_min{};
  for (std::size_t k = 0; k < 4; ++k) {
    for (const Eigen::Vector2d& p : points) {
      if (std::abs(distance(coarse.sides[k], p)) <= SquareRefiner::kGatherWidths * kTape) near[k].push_back(p);
    }
    const std::size_t stride = (near[k].size() + SquareRefiner::kWidePassPoints - 1) / SquareRefiner::kWidePassPoints;
    for (std::size_t i = 0; i < near[k].size(); i += stride) sampled[k].push_back(near[k][i]);
    sampled_min[k] = (10 + stride - 1) / stride;
  }
  std::array<PlaneLine, 4> lines = coarse.sides;
  const auto meet = [&](std::array<Eigen::Vector2d, 4>& out) {
    for (std::size_t k = 0; k < 4; ++k) {
      SideFit a{lines[k], 0, 0}, b{lines[(k + 1) % 4], 0, 0};
      if (!intersect(a.line, b.line, out[k])) return false;
    }
    return true;
  };
  if (!meet(corners)) return false;
  for (int pass = 0; pass < passes; ++pass) {
    std::array<PlaneLine, 4> refined;
    const Eigen::Vector2d centre = (corners[0] + corners[1] + corners[2] + corners[3]) / 4;
    const bool last = pass + 1 == passes;
    for (std::size_t k = 0; k < 4; ++k) {
      const PlaneLine& before = lines[(k + 3) % 4];
      const PlaneLine& after = lines[(k + 1) % 4];
      const double in_before = distance(before, centre) > 0 ? 1 : -1, in_after = distance(after, centre) > 0 ? 1 : -1;
      std::vector<Eigen::Vector2d> side;
      for (const Eigen::Vector2d& p : last ? near[k] : sampled[k]) {
        const double band = last ? 0.75 * kTape : kTape;
        if (std::abs(distance(lines[k], p)) <= band && in_before * distance(before, p) >= kTape &&
            in_after * distance(after, p) >= kTape) {
          side.push_back(p);
        }
      }
      if (side.size() < (last ? 10 : sampled_min[k])) return false;
      Eigen::Vector2d mean = Eigen::Vector2d::Zero();
      for (const Eigen::Vector2d& p : side) mean += p / static_cast<double>(side.size());
      Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
      for (const Eigen::Vector2d& p : side) scatter += (p - mean) * (p - mean).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
      Eigen::Vector2d n = solver.eigenvectors().col(0);  // least spread
      if (n.dot(normal(lines[k])) < 0) n = -n;
      refined[k] = {std::atan2(n.y(), n.x()), n.dot(mean), 0};
    }
    lines = refined;
    if (!meet(corners)) return false;
  }
  return true;
}

TEST(SideRefinement, MatchesTheReferenceAndTheTruth) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 0.004);
  std::uniform_real_distribution<double> across(-kTape / 2, kTape / 2), unit(0, 1);
  const double yaw = 0.4;
  const Eigen::Vector2d centre(0.7, -0.4);
  const Eigen::Rotation2Dd turn(yaw);
  std::array<Eigen::Vector2d, 4> truth;
  for (std::size_t k = 0; k < 4; ++k) {
    const double x = k == 1 || k == 2 ? 1 : -1, y = k >= 2 ? 1 : -1;
    truth[k] = centre + turn * Eigen::Vector2d(x, y);
  }
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d a = truth[k], b = truth[(k + 1) % 4];
    const Eigen::Vector2d u = (b - a).normalized(), n(-u.y(), u.x());
    for (double s = -kTape / 2; s <= 2 + kTape / 2; s += 0.003) {
      if (k != 0 && std::fmod(s + 1, 0.2) >= 0.1) continue;  // dashed
      points.push_back(a + s * u + (across(rng) + noise(rng)) * n);
    }
  }
  // A strip of safety tape 15 cm beside side 3, and a lamp's scattered points inside.
  const Eigen::Vector2d u2 = (truth[3] - truth[2]).normalized(), n2(-u2.y(), u2.x());
  for (double s = 0.3; s < 1.5; s += 0.004) points.push_back(truth[2] + s * u2 + (0.15 + across(rng)) * n2);
  for (int i = 0; i < 500; ++i) points.push_back(centre + Eigen::Vector2d(unit(rng) - 0.5, unit(rng) - 0.5));

  // The coarse sides of the truth (theta the normal toward the outside, as any), perturbed.
  const auto coarse_of = [&](double shift, double tilt) {
    SquareSides sides;
    for (std::size_t k = 0; k < 4; ++k) {
      const Eigen::Vector2d a = truth[(k + 3) % 4], b = truth[k];  // side k ends at corner k
      const Eigen::Vector2d u = (b - a).normalized();
      const double theta = std::atan2(u.x(), -u.y()) + (k % 2 == 0 ? tilt : -tilt);
      const Eigen::Vector2d n(std::cos(theta), std::sin(theta));
      sides.sides[k] = {theta, n.dot(a) + (k == 1 ? shift : 0.01 * static_cast<double>(k)), 0};
    }
    return sides;
  };
  for (const auto& [shift, tilt] : {std::pair{0.0, 0.0}, std::pair{0.02, 0.01}, std::pair{-0.03, -0.015},
                                    std::pair{0.05, 0.04}, std::pair{0.2, 0.0}}) {
    SCOPED_TRACE(testing::Message() << "shift " << shift << " tilt " << tilt);
    const SquareSides coarse = coarse_of(shift, tilt);
    std::array<Eigen::Vector2d, 4> expected;
    const bool reference_ok = reference_refine(points, coarse, 3, expected);
    SquareFit fit;
    SquareRefiner refiner(points.size());
    const bool ok = refiner.refine(points, coarse, kTape, 3, 10, fit);
    ASSERT_EQ(ok, reference_ok);
    EXPECT_TRUE(ok || std::abs(shift) > 0.1);
    if (!ok) continue;
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_NEAR((fit.corners[k] - expected[k]).norm(), 0, 1e-9) << "corner " << k;
      EXPECT_LT((fit.corners[k] - truth[k]).norm(), 0.01) << "corner " << k;
    }
  }
}

// traces_corner: which coarse hypotheses are the refined square again (the detector merges them)
// and which are another square. Lines: x cos(theta) + y sin(theta) = rho.
TEST(SideRefinement, TracesACornerOfTheRefinedSquareOnly) {
  constexpr double kRight = std::numbers::pi / 2, kDegree = std::numbers::pi / 180;
  const auto sides_of = [](std::array<PlaneLine, 4> lines) {
    SquareSides sides;
    sides.sides = lines;
    return sides;
  };
  // The refined square: x = -1, y = -1, x = 1, y = 1; corner k where side k meets side k + 1.
  SquareFit fit;
  fit.corners = {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1), Eigen::Vector2d(-1, 1)};
  // Its sides x = -1 and y = -1 within 2 cm and a degree, the others a stray strip's line and a
  // skewed weak one.
  EXPECT_TRUE(traces_corner(sides_of({{{0.5 * kDegree, -1.01, 4}, {kRight + 1 * kDegree, -1.02, 3},
                                       {14 * kDegree, 0.8, 2}, {kRight + 6 * kDegree, 0.9, 2}}}),
                            fit, 2 * kTape));
  // Every side through another line 2 degrees off (a skewed view's other column pair), the line
  // theta + pi with rho negated among them.
  EXPECT_TRUE(traces_corner(sides_of({{{2 * kDegree, -0.98, 1}, {-kRight + 2 * kDegree, 1.0, 1},
                                       {2 * kDegree, 1.02, 1}, {kRight + 2 * kDegree, 1.0, 1}}}),
                            fit, 2 * kTape));
  // The square beside it, 2.5 m on: y = -1 and y = 1 are its lines too, but no corner is.
  EXPECT_FALSE(traces_corner(sides_of({{{0, 1.5, 9}, {kRight, -1, 9}, {0, 3.5, 9}, {kRight, 1, 9}}}), fit, 2 * kTape));
  // x = +-1.15 (strips 15 cm beside two sides) with the true y sides: no corner.
  EXPECT_FALSE(traces_corner(sides_of({{{0, -1.15, 9}, {kRight, -1, 9}, {0, 1.15, 9}, {kRight, 1, 9}}}), fit, 2 * kTape));
  // A line 6 degrees off a side runs 10 cm from one of its ends: not that side.
  EXPECT_FALSE(traces_corner(sides_of({{{6 * kDegree, -1.0, 9}, {kRight + 6 * kDegree, -1.0, 9}, {0, 1, 9}, {kRight, 5, 9}}}),
                             fit, 2 * kTape));
}

// side_ridges: a strip of tape beside a side is a ridge of its own, found beside the side's
// wherever the fitted line lies between them; a side without one, among scattered points, has
// one ridge. Lines: x cos(theta) + y sin(theta) = rho.
TEST(SideRefinement, FindsTheRidgeOfAStripBesideASide) {
  constexpr double kRight = std::numbers::pi / 2;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> across(-0.5, 0.5), unit(0, 1);
  // The square x = -1, y = -1, x = 1, y = 1 (side k ends at corner k), y = -1 solid.
  const std::array<Eigen::Vector2d, 4> corners{Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1),
                                               Eigen::Vector2d(-1, 1)};
  std::vector<Eigen::Vector2d> points;
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d a = corners[(k + 3) % 4], b = corners[k];
    const Eigen::Vector2d u = (b - a).normalized(), n(-u.y(), u.x());
    for (double s = 0; s <= 2; s += 0.004) {
      if (k != 1 && std::fmod(s, 0.2) >= 0.1) continue;  // dashed
      points.push_back(a + s * u + kTape * across(rng) * n);
    }
  }
  // An 8 cm strip 9 cm outside x = 1 (2.5 cm of ceiling between it and the tape), a 5 cm one 12 cm
  // inside y = 1, points scattered inside.
  for (double y = -0.9; y < 0.9; y += 0.002) points.push_back({1.09 + 0.08 * across(rng), y});
  for (double x = -0.6; x < 0.4; x += 0.004) points.push_back({x, 0.88 + kTape * across(rng)});
  for (int i = 0; i < 500; ++i) points.push_back({2 * unit(rng) - 1, 2 * unit(rng) - 1});

  SquareFit fit;
  fit.corners = corners;
  // The fitted x = 1 pulled 4 cm toward the strip: between the two ridges.
  fit.sides = {SideFit{{0, -1, 0}, 0, 0}, SideFit{{kRight, -1, 0}, 0, 0}, SideFit{{0, 1.04, 0}, 0, 0},
               SideFit{{kRight, 1, 0}, 0, 0}};
  const SquareRefiner::SideRidges ridges = SquareRefiner::side_ridges(points, fit, kTape, 10);
  const auto has_ridge_at = [&](std::size_t k, double offset, double within = 0.005) {
    for (std::size_t r = 0; r < ridges.count[k]; ++r) {
      if (std::abs(ridges.offsets[k][r] - offset) < within) return true;
    }
    return false;
  };
  for (const std::size_t k : {std::size_t{0}, std::size_t{1}}) {
    EXPECT_EQ(ridges.count[k], 1u) << "side " << k;
    EXPECT_TRUE(has_ridge_at(k, 0)) << "side " << k;
  }
  EXPECT_EQ(ridges.count[2], 2u);
  EXPECT_TRUE(has_ridge_at(2, -0.04));  // the tape
  EXPECT_TRUE(has_ridge_at(2, 0.05, 0.02));  // the strip, a tape width of it
  EXPECT_EQ(ridges.count[3], 2u);
  EXPECT_TRUE(has_ridge_at(3, 0));
  EXPECT_TRUE(has_ridge_at(3, -0.12));
}

// straighten: a 7 cm strip that starts on a side's tape and leaves it at 4 degrees pulls the
// refined side toward it; the straightened side lies on the tape again (the strip's points left
// within the band of its first segments still pull a little). A clean square is left as it is.
TEST(SideRefinement, StraightensASideThatAStripTouches) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> across(-0.5, 0.5);
  const std::array<Eigen::Vector2d, 4> truth{Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1),
                                             Eigen::Vector2d(-1, 1)};
  std::vector<Eigen::Vector2d> points;
  SquareSides coarse;
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d a = truth[(k + 3) % 4], b = truth[k];  // side k ends at corner k
    const Eigen::Vector2d u = (b - a).normalized(), n(-u.y(), u.x());
    for (double s = -kTape / 2; s <= 2 + kTape / 2; s += 0.003) {
      if (k != 1 && std::fmod(s + 1, 0.2) >= 0.1) continue;  // dashed
      for (int i = 0; i < 4; ++i) points.push_back(a + s * u + kTape * across(rng) * n);
    }
    coarse.sides[k] = {std::atan2(n.y(), n.x()), n.dot(a) + 0.01, 0};
  }
  SquareRefiner refiner(points.size() + 2000);
  const auto corner_error = [&](const SquareFit& fit) {
    double worst = 0;
    for (std::size_t k = 0; k < 4; ++k) worst = std::max(worst, (fit.corners[k] - truth[k]).norm());
    return worst;
  };
  SquareFit clean;
  ASSERT_TRUE(refiner.refine(points, coarse, kTape, 6, 10, clean));
  const SquareFit refined = clean;
  EXPECT_FALSE(refiner.straighten(kTape, 10, clean));
  EXPECT_EQ(clean.corners, refined.corners);

  // The strip along y = -1 (side 0) from x = -0.9, its inner edge on the tape's centre line.
  const double angle = 4 * std::numbers::pi / 180;
  const Eigen::Vector2d along(std::cos(angle), -std::sin(angle)), out(-std::sin(angle), -std::cos(angle));
  for (double s = 0; s < 0.8; s += 0.003) {
    for (int i = 0; i < 6; ++i) {
      points.push_back(Eigen::Vector2d(-0.9, -1) + s * along + (0.035 + 0.07 * across(rng)) * out);
    }
  }
  SquareFit fit;
  ASSERT_TRUE(refiner.refine(points, coarse, kTape, 6, 10, fit));
  EXPECT_GT(corner_error(fit), 0.015);  // measured: 19 mm (clean: 1.5 mm)
  ASSERT_TRUE(refiner.straighten(kTape, 10, fit));
  EXPECT_LT(corner_error(fit), 0.006);  // measured: 4.8 mm
}

}  // namespace
}  // namespace irloc::square
