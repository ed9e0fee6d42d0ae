// The square path among other retro-reflective things: strips of safety tape on ducts and
// furniture, and crescent reflectors (a round sticker half in shadow), near the square, with the
// robot anywhere in the area below it, with and without people hiding part of a side. Nothing may
// ever be reported at a wrong pose. The pose rates asserted are the ones measured (see
// docs/square_markers.md): they guard against losing ground.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "algo/markers/square/square_detector.hpp"
#include "tests/square/square_scenes.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

constexpr double kDegree = std::numbers::pi / 180;

// Clutter layouts around the default 2 m square centred at the origin (sides at +-1 m).
std::vector<std::vector<Clutter>> layouts() {
  using Kind = Clutter::Kind;
  return {
      // A duct's strip parallel to a side, just outside it.
      {{Kind::strip, {0.0, -1.22}, 0.0, 1.8, 0.05}},
      // A strip parallel to a side, inside the square.
      {{Kind::strip, {0.6, 0.1}, std::numbers::pi / 2, 1.6, 0.05}},
      // Two strips beyond opposite sides: a wider "square" of stray lines.
      {{Kind::strip, {-1.18, 0.0}, std::numbers::pi / 2, 2.2, 0.05}, {Kind::strip, {1.18, 0.2}, std::numbers::pi / 2, 2.0, 0.05}},
      // Crescents beside two sides and a strip crossing near a corner.
      {{Kind::crescent, {0.3, 1.15}, -std::numbers::pi / 2, 0, 0.10},
       {Kind::crescent, {1.2, -0.4}, std::numbers::pi, 0, 0.12},
       {Kind::strip, {-1.3, -1.3}, std::numbers::pi / 4, 1.2, 0.05}},
  };
}

// Poses found, gross errors (beyond 5 cm or 1 degree) and the squared errors of the others.
struct Tally {
  int cases = 0, found = 0, gross = 0;
  double squared_position = 0, squared_yaw = 0;

  double position_rms() const { return std::sqrt(squared_position / std::max(found - gross, 1)); }
  double yaw_rms() const { return std::sqrt(squared_yaw / std::max(found - gross, 1)); }
  void print(const char* what) const {
    std::printf("%s: %d of %d found, %d gross, position RMS %.2f mm, yaw RMS %.3f deg\n", what, found, cases, gross,
                1000 * position_rms(), yaw_rms() / kDegree);
  }
};

void tally_detection(const TapeScene& scene, const SquareDetection& detection, Tally& tally) {
  ++tally.cases;
  if (!detection.found()) return;
  ++tally.found;
  const Eigen::Vector3d& t = detection.world_from_base.translation;
  const double position = std::hypot(t.x() - scene.x, t.y() - scene.y);
  const double yaw = std::abs(wrap_angle(rpy_from_rotation(detection.world_from_base.rotation).yaw - scene.yaw));
  if (position > 0.05 || yaw > 1 * kDegree) {
    ++tally.gross;
    return;
  }
  tally.squared_position += position * position;
  tally.squared_yaw += yaw * yaw;
}

SquareDetection detect(SquareDetector& detector, const Image8& on, const Image8& off) {
  const ImageView8 on_view(on.view()), off_view(off.view());
  return detector.detect(on_view, off_view, shared_noise(on_view, off_view));
}

void run(const TapeScene& scene, Tally& tally) {
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  Image8 on, off;
  scene.render(on, off);
  tally_detection(scene, detect(detector, on, off), tally);
}

TapeScene scene_at(double x, double y, double yaw, const std::vector<Clutter>& clutter, unsigned seed) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.x = x;
  scene.y = y;
  scene.yaw = yaw;
  scene.clutter = clutter;
  scene.seed = seed;
  return scene;
}

TEST(SquareClutter, StrayLinesNearTheSquareNeverGiveAWrongPose) {
  Tally tally;
  unsigned seed = 1;
  for (const std::vector<Clutter>& clutter : layouts()) {
    for (const double x : {-1.5, 0.0, 1.5}) {
      for (const double y : {-1.5, 0.0, 1.5}) run(scene_at(x, y, 0.4 * x + 0.7 * y, clutter, seed++), tally);
    }
  }
  tally.print("clutter");
  EXPECT_EQ(tally.gross, 0);
  EXPECT_GE(tally.found, 36);  // measured: 36 of 36 (30 before the level search and the dash phase)
  EXPECT_LT(tally.position_rms(), 0.015);
  EXPECT_LT(tally.yaw_rms(), 0.5 * kDegree);
}

TEST(SquareClutter, StrayLinesAndPeopleNeverGiveAWrongPose) {
  Tally tally;
  unsigned seed = 100;
  int side = 0;
  for (const std::vector<Clutter>& clutter : layouts()) {
    for (const double x : {-1.5, 0.0, 1.5}) {
      for (const double y : {-1.5, 1.5}) {
        TapeScene scene = scene_at(x, y, -0.5 * x + 0.3 * y, clutter, seed++);
        const double hidden = 0.6 + 0.4 * (seed % 2);  // 30 % or 50 % of the side
        scene.hidden.push_back({side++ % 4, 0.5, 0.5 + hidden});
        run(scene, tally);
      }
    }
  }
  tally.print("clutter and people");
  EXPECT_EQ(tally.gross, 0);
  EXPECT_GE(tally.found, 24);  // measured: 24 of 24 (14 before)
  EXPECT_LT(tally.position_rms(), 0.015);
  EXPECT_LT(tally.yaw_rms(), 0.5 * kDegree);
}

// The goal's camera (1280 x 1024 equisolid fisheye, the 2 m square 2 m above it), the robot
// anywhere in the 4 m x 4 m area below the square at any heading, random clutter; each scene
// once as it is and once with a person hiding 30-50 % of a random side.
TEST(SquareClutter, AtTheGoalResolutionAnywhereInTheArea) {
  constexpr int kScenes = 8;
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> uniform(0, 1);
  TapeScene scene = scene_at(0, 0, 0, {}, 1);
  scene.camera = fisheye(1280, 1024);
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  Tally clutter, people;
  Image8 on, off;
  for (int k = 0; k < kScenes; ++k) {
    scene.x = 4 * uniform(rng) - 2;
    scene.y = 4 * uniform(rng) - 2;
    scene.yaw = std::numbers::pi * (2 * uniform(rng) - 1);
    scene.clutter = random_clutter(rng);
    scene.seed = static_cast<unsigned>(500 + k);
    scene.hidden.clear();
    const std::vector<Eigen::Vector2d> hits = scene.ceiling_hits();
    scene.render(hits, on, off);
    tally_detection(scene, detect(detector, on, off), clutter);
    const double hidden = 0.6 + 0.4 * uniform(rng);
    const double from = 0.1 + (1.8 - hidden) * uniform(rng);
    scene.hidden.push_back({static_cast<int>(4 * uniform(rng)), from, from + hidden});
    scene.render(hits, on, off);
    tally_detection(scene, detect(detector, on, off), people);
  }
  clutter.print("1280 x 1024, clutter");
  people.print("1280 x 1024, clutter and people");
  EXPECT_EQ(clutter.gross + people.gross, 0);
  EXPECT_GE(clutter.found, kScenes);  // measured: 8 of 8 (7 of 8 before the level search and the dash phase)
  EXPECT_GE(people.found, kScenes);   // measured: 8 of 8 (8 of 8 before)
  EXPECT_LT(clutter.position_rms(), 0.015);
  EXPECT_LT(clutter.yaw_rms(), 0.5 * kDegree);
  EXPECT_LT(people.position_rms(), 0.015);
  EXPECT_LT(people.yaw_rms(), 0.5 * kDegree);
}

// Two scenes of bench_square_goal (rounded) where clutter crosses a dashed side (and in the second
// a person hides half of another): that side reads neither solid nor dashed, the other three are
// clear. It must not veto them.
TEST(SquareClutter, ASideThatReadsNeitherDoesNotVetoTheOtherThree) {
  using Kind = Clutter::Kind;
  TapeScene crossed = scene_at(-1.646, 1.105, 121.0 * kDegree,
                               {{Kind::strip, {1.11, 0.66}, 81.1 * kDegree, 2.17, 0.064},
                                {Kind::strip, {0.85, 0.45}, 71.1 * kDegree, 1.34, 0.061},
                                {Kind::strip, {-0.72, -0.64}, 270.0 * kDegree, 0.99, 0.068},
                                {Kind::crescent, {1.41, 0.03}, 204.2 * kDegree, 0, 0.063}},
                               1020);
  TapeScene hidden = scene_at(1.502, -0.120, -54.8 * kDegree,
                              {{Kind::crescent, {0.75, -1.30}, 57.2 * kDegree, 0, 0.112},
                               {Kind::crescent, {1.21, 0.10}, 108.5 * kDegree, 0, 0.145},
                               {Kind::crescent, {-1.09, 0.73}, 15.1 * kDegree, 0, 0.148}},
                              1177);
  hidden.hidden.push_back({3, 0.18, 1.09});
  for (TapeScene* scene : {&crossed, &hidden}) {
    scene->camera = fisheye(1280, 1024);
    SquareDetector detector(scene->camera, 8, to_rigid(scene->mount), Dof::planar3, scene->marker, SquareConfig{});
    Image8 on, off;
    scene->render(on, off);
    const SquareDetection detection = detect(detector, on, off);
    ASSERT_TRUE(detection.found()) << to_string(detection.outcome);
    Tally tally;
    tally_detection(*scene, detection, tally);
    EXPECT_EQ(tally.gross, 0);
    EXPECT_LT(tally.position_rms(), 0.015);
  }
}

// A scene of bench_square_goal (rounded) with the robot tilted by roll and pitch (degrees).
TapeScene tilted_scene_at(double x, double y, double yaw, double roll, double pitch, const std::vector<Clutter>& clutter,
                          unsigned seed) {
  TapeScene scene = scene_at(x, y, yaw, clutter, seed);
  scene.camera = fisheye(1280, 1024);
  scene.roll = roll * kDegree;
  scene.pitch = pitch * kDegree;
  return scene;
}

// The scene's pose found under dof 6, not gross and within the goal's accuracy.
void expect_tilted_pose(const TapeScene& scene) {
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::full6, scene.marker, SquareConfig{});
  Image8 on, off;
  scene.render(on, off);
  const SquareDetection detection = detect(detector, on, off);
  ASSERT_TRUE(detection.found()) << to_string(detection.outcome);
  Tally tally;
  tally_detection(scene, detection, tally);
  EXPECT_EQ(tally.gross, 0);
  EXPECT_LT(tally.position_rms(), 0.015);
}

// Two tilted scenes with strips beside two sides: a hypothesis that takes a strip for a side fits
// a square at some other tilt and is scored first. Each hypothesis's dash patterns must be read
// on the tape levelled at its own tilt, not at the tilt of the first one that fitted.
TEST(SquareClutter, ATiltedRobotReadsEachHypothesisAtItsOwnTilt) {
  using Kind = Clutter::Kind;
  expect_tilted_pose(tilted_scene_at(1.845, -0.298, 72.3 * kDegree, 0.70, -0.36,
                                     {{Kind::strip, {0.615, 0.606}, 180.0 * kDegree, 1.99, 0.041},
                                      {Kind::strip, {0.322, -1.085}, 0.0 * kDegree, 2.10, 0.062},
                                      {Kind::strip, {0.144, -1.396}, -10.9 * kDegree, 1.79, 0.053}},
                                     1099));
  expect_tilted_pose(tilted_scene_at(1.866, 0.365, 21.9 * kDegree, 2.02, 0.53,
                                     {{Kind::strip, {0.305, -0.919}, 0.0 * kDegree, 2.28, 0.044},
                                      {Kind::crescent, {-1.305, 0.547}, 355.0 * kDegree, 0, 0.130},
                                      {Kind::crescent, {-0.441, -1.214}, 122.9 * kDegree, 0, 0.098},
                                      {Kind::strip, {-1.088, -0.067}, 270.0 * kDegree, 1.23, 0.038}},
                                     1168));
}

// Tilted scenes with strips 9-17 cm beside one or two sides, stronger than the tape: every
// hypothesis takes a strip for a side (its line is the strip's, or the refinement, pulled by both,
// settles between them; the true line may be no Hough peak at all). Refitted on the other ridge
// of points beside those sides, the square passes.
TEST(SquareClutter, ASideBesideAStripIsRefittedOnItsOwnRidge) {
  using Kind = Clutter::Kind;
  // Strips 12 cm inside one side and 11 cm outside another.
  expect_tilted_pose(tilted_scene_at(1.811, 0.265, -61.8 * kDegree, -1.94, -3.04,
                                     {{Kind::strip, {-0.884, -0.054}, 270.0 * kDegree, 1.82, 0.074},
                                      {Kind::strip, {-0.019, 1.111}, 180.0 * kDegree, 2.21, 0.043},
                                      {Kind::crescent, {-0.761, 0.206}, 239.5 * kDegree, 0, 0.091}},
                                     1025));
  // Strips beside three sides; two hypotheses' sides are both strips.
  expect_tilted_pose(tilted_scene_at(0.421, -0.614, 70.5 * kDegree, 2.67, 2.42,
                                     {{Kind::strip, {0.826, 0.731}, 90.0 * kDegree, 1.70, 0.056},
                                      {Kind::strip, {-0.479, -1.329}, 0.0 * kDegree, 2.32, 0.058},
                                      {Kind::strip, {-0.624, -1.111}, 6.4 * kDegree, 1.90, 0.071},
                                      {Kind::strip, {-0.504, 0.626}, 180.0 * kDegree, 1.81, 0.045}},
                                     1108));
  // An 8 cm strip 9 cm outside the solid side: 2.5 cm of ceiling between them.
  expect_tilted_pose(tilted_scene_at(1.818, 1.829, -3.0 * kDegree, 2.92, -0.54,
                                     {{Kind::strip, {1.093, -0.069}, 90.0 * kDegree, 1.92, 0.079},
                                      {Kind::strip, {-0.062, -0.643}, -47.0 * kDegree, 0.88, 0.057},
                                      {Kind::strip, {0.700, 0.191}, 75.0 * kDegree, 0.95, 0.033}},
                                     1180));
  // Strips 12 cm outside and 18 cm inside one side, the true line no Hough peak.
  expect_tilted_pose(tilted_scene_at(1.521, 1.817, 96.5 * kDegree, -1.99, -3.43,
                                     {{Kind::strip, {0.823, 0.508}, 90.0 * kDegree, 0.52, 0.060},
                                      {Kind::strip, {-1.356, 0.033}, 270.0 * kDegree, 1.00, 0.072},
                                      {Kind::strip, {1.123, 0.553}, 90.0 * kDegree, 1.16, 0.055},
                                      {Kind::strip, {0.475, 1.099}, 180.0 * kDegree, 0.80, 0.051}},
                                     1193));
}

// A tilted scene (bench_square_goal --seed=7, scene 176, rounded): a 7 cm strip starts on the
// tape of a far side and leaves it at a few degrees. The refined side settles between them, and
// the 6-dof fit takes up the error in its tilt: without straightening, the pose was 7.8 cm off
// with a corner RMS of 11 mm, within the check.
TEST(SquareClutter, ASideTouchedByAStripIsStraightened) {
  using Kind = Clutter::Kind;
  expect_tilted_pose(tilted_scene_at(-1.093, 1.288, -87.9 * kDegree, 2.38, -3.35,
                                     {{Kind::strip, {-0.535, 1.091}, 189.6 * kDegree, 0.75, 0.070},
                                      {Kind::crescent, {-1.244, -0.516}, 234.6 * kDegree, 0, 0.050}},
                                     1176));
}

// A second square of the same pattern beside the mapped one, the robot between them: both explain
// the tape equally well, and nothing tells which is the mapped one: no pose.
TEST(SquareClutter, TwoSquaresThatExplainTheTapeEquallyGiveNoPose) {
  TapeScene scene = scene_at(1.25, 0.0, 0.0, {}, 7);
  scene.other_squares.push_back(tape_square(2.5, 0.0, 0.0));
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  Image8 on, off;
  scene.render(on, off);
  const SquareDetection detection = detect(detector, on, off);
  EXPECT_EQ(detection.outcome, SquareOutcome::ambiguous);
  EXPECT_GE(detection.hypotheses_found, 2u);
}

}  // namespace
}  // namespace irloc::test
