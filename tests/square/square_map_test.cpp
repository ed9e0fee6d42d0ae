// Several squares in one map (docs/square_markers.md, "Several squares"): each is identified by
// its dash pattern, two of one pattern by the last pose; two in view are fused; a square that
// cannot be identified gives no pose, never one from the wrong square.

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "algo/markers/square/square_detector.hpp"
#include "tests/square/square_scenes.hpp"
#include "tests/square/tape_scene.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

struct Seen {
  SquareDetection detection;
  TapeScene scene;
};

// The robot at (dx, dy, yaw) relative to square `under`'s centre; every square of the map painted.
Seen look(const std::vector<SquareMarker>& map, std::size_t under, double dx, double dy, double yaw,
          const RigidTransform* prior, unsigned seed) {
  Seen seen;
  TapeScene& scene = seen.scene;
  scene.camera = fisheye(400, 320);
  scene.marker = map[under];
  for (std::size_t k = 0; k < map.size(); ++k) {
    if (k != under) scene.other_squares.push_back(map[k]);
  }
  const Eigen::Vector3d centre = (map[under].corners[0] + map[under].corners[2]) / 2;
  scene.x = centre.x() + dx;
  scene.y = centre.y() + dy;
  scene.yaw = yaw;
  scene.seed = seed;
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, map, SquareConfig{});
  Image8 on, off;
  scene.render(on, off);
  const ImageView8 on_view(on.view()), off_view(off.view());
  seen.detection = detector.detect(on_view, off_view, shared_noise(on_view, off_view), prior);
  return seen;
}

double position_error(const Seen& seen) {
  const Eigen::Vector3d& t = seen.detection.world_from_base.translation;
  return std::hypot(t.x() - seen.scene.x, t.y() - seen.scene.y);
}

RigidTransform pose_at(double x, double y, double yaw) {
  RigidTransform pose;
  pose.rotation = rotation_from_rpy(0, 0, yaw);
  pose.translation = Eigen::Vector3d(x, y, 0);
  return pose;
}

TEST(SquareMap, EachSquareIsIdentifiedByItsPatternAndTheLastPose) {
  const std::vector<SquareMarker> map = map_of_four();
  const double offsets[][3] = {{0.0, 0.0, 0.2}, {-0.6, 0.4, 1.9}, {0.5, -0.5, -2.4}};
  int found_with_prior = 0, cases = 0;
  for (std::size_t under = 0; under < map.size(); ++under) {
    for (const auto& o : offsets) {
      ++cases;
      const unsigned seed = static_cast<unsigned>(7 + cases);
      // With a recent pose 0.3 m off the truth: the right square, or none.
      const Eigen::Vector3d centre = (map[under].corners[0] + map[under].corners[2]) / 2;
      const RigidTransform prior = pose_at(centre.x() + o[0] + 0.3, centre.y() + o[1], o[2]);
      const Seen seen = look(map, under, o[0], o[1], o[2], &prior, seed);
      if (seen.detection.found()) {
        ++found_with_prior;
        EXPECT_EQ(seen.detection.squares[0], static_cast<int>(under)) << map[under].name;
        EXPECT_LT(position_error(seen), 0.015) << map[under].name;
      }
      // Without a pose: two squares share each pattern, so the square is not identified.
      const Seen alone = look(map, under, o[0], o[1], o[2], nullptr, seed);
      EXPECT_FALSE(alone.detection.found()) << map[under].name;
      if (!alone.detection.found() && seen.detection.found()) {
        EXPECT_EQ(alone.detection.outcome, SquareOutcome::unidentified) << map[under].name;
      }
    }
  }
  std::printf("identified with a recent pose: %d of %d\n", found_with_prior, cases);
  EXPECT_GE(found_with_prior, cases - 1);
}

TEST(SquareMap, APatternOfItsOwnNeedsNoPose) {
  // a1 and b1 only: each pattern names one square.
  const std::vector<SquareMarker> map = {map_of_four()[0], map_of_four()[1]};
  for (std::size_t under = 0; under < map.size(); ++under) {
    const Seen seen = look(map, under, 0.3, -0.2, 0.7, nullptr, 3);
    ASSERT_TRUE(seen.detection.found()) << map[under].name << ": " << to_string(seen.detection.outcome);
    EXPECT_EQ(seen.detection.squares[0], static_cast<int>(under));
    EXPECT_LT(position_error(seen), 0.015);
  }
}

TEST(SquareMap, APatternNotInTheMapGivesNoPose) {
  // The robot under b1, whose pattern the map does not have (a1 only, and a square of period 0.45).
  const std::vector<SquareMarker> four = map_of_four();
  const std::vector<SquareMarker> map = {four[0], patterned(tape_square(0, 20, 0), "c", 0.30, 0.15)};
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.marker = four[1];
  scene.x = 6.2;
  scene.y = 0.1;
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, map, SquareConfig{});
  Image8 on, off;
  scene.render(on, off);
  const ImageView8 on_view(on.view()), off_view(off.view());
  const RigidTransform prior = pose_at(6.2, 0.1, 0);
  const SquareDetection detection = detector.detect(on_view, off_view, shared_noise(on_view, off_view), &prior);
  EXPECT_FALSE(detection.found()) << "square " << detection.squares[0];
}

TEST(SquareMap, TwoSquaresInViewAreFused) {
  // Two squares of different patterns side by side, 0.4 m apart; the robot between them.
  const std::vector<SquareMarker> map = {patterned(tape_square(-1.2, 0, 0), "west", 0.10, 0.10),
                                         patterned(tape_square(1.2, 0, 0), "east", 0.20, 0.10)};
  int fused = 0;
  const double spots[][3] = {{0.0, 0.0, 0.0}, {0.1, -0.2, 0.5}, {-0.1, 0.15, 2.0}};
  for (const auto& spot : spots) {
    TapeScene scene;
    scene.camera = fisheye(480, 384);
    scene.marker = map[0];
    scene.other_squares = {map[1]};
    scene.x = spot[0];
    scene.y = spot[1];
    scene.yaw = spot[2];
    SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, map, SquareConfig{});
    Image8 on, off;
    scene.render(on, off);
    const ImageView8 on_view(on.view()), off_view(off.view());
    const SquareDetection detection = detector.detect(on_view, off_view, shared_noise(on_view, off_view));
    ASSERT_TRUE(detection.found()) << to_string(detection.outcome);
    const Eigen::Vector3d& t = detection.world_from_base.translation;
    EXPECT_LT(std::hypot(t.x() - scene.x, t.y() - scene.y), 0.015);
    fused += detection.square_count == 2;
    if (detection.square_count == 2) {
      EXPECT_NE(detection.squares[0], detection.squares[1]);
    }
  }
  EXPECT_GE(fused, 2);
}

TEST(SquareMap, RefusesSquaresTheSharedStagesCannotServe) {
  const SquareMarker base = tape_square(0, 0, 0);
  const TapeScene scene;
  const auto make = [&](const std::vector<SquareMarker>& map) {
    SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, map, SquareConfig{});
  };
  EXPECT_THROW(make({base, patterned(tape_square(5, 0, 0), "b", 0.12, 0.12)}), std::invalid_argument);  // too alike
  EXPECT_THROW(make({base, tape_square(5, 0, 0, 1.5)}), std::invalid_argument);                           // side
  SquareMarker higher = tape_square(5, 0, 0);
  for (auto& corner : higher.corners) corner.z() += 0.2;
  EXPECT_THROW(make({base, higher}), std::invalid_argument);
  SquareMarker wider = tape_square(5, 0, 0);
  wider.tape_width = 0.08;
  EXPECT_THROW(make({base, wider}), std::invalid_argument);
  EXPECT_NO_THROW(make({base, patterned(tape_square(5, 0, 0), "b", 0.15, 0.15)}));
}

}  // namespace
}  // namespace irloc::test
