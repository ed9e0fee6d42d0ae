// The square path end to end on ray-cast fisheye frames with known ground truth.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "algo/markers/square/square_detector.hpp"
#include "tests/square/tape_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

constexpr double kDegree = std::numbers::pi / 180;

struct Rendered {
  Image8 on, off;
};

Rendered render(const TapeScene& scene) {
  Rendered frames;
  scene.render(frames.on, frames.off);
  return frames;
}

DifferenceNoise noise_of(const Rendered& frames) { return shared_noise(ImageView8(frames.on.view()), ImageView8(frames.off.view())); }

SquareDetection detect(const TapeScene& scene, const SquareMarker& map_marker, const Rendered& frames) {
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, map_marker, SquareConfig{});
  return detector.detect(ImageView8(frames.on.view()), ImageView8(frames.off.view()), noise_of(frames));
}

double yaw_of(const RigidTransform& pose) { return std::atan2(pose.rotation(1, 0), pose.rotation(0, 0)); }

void expect_pose(const SquareDetection& detection, const TapeScene& scene, double position_tolerance,
                 double yaw_tolerance) {
  ASSERT_TRUE(detection.found()) << to_string(detection.outcome);
  const Eigen::Vector3d& t = detection.world_from_base.translation;
  EXPECT_NEAR(t.x(), scene.x, position_tolerance);
  EXPECT_NEAR(t.y(), scene.y, position_tolerance);
  EXPECT_EQ(t.z(), 0);
  EXPECT_NEAR(wrap_angle(yaw_of(detection.world_from_base) - scene.yaw), 0, yaw_tolerance);
  EXPECT_GT(detection.confidence, 0.3);
  EXPECT_LE(detection.confidence, 1.0);
}

struct Placement {
  double x, y, yaw;
};

class SquareDetectorPoses : public testing::TestWithParam<Placement> {};

TEST_P(SquareDetectorPoses, FindsThePoseOverTheAreaAtAnyHeading) {
  TapeScene scene;
  scene.x = GetParam().x;
  scene.y = GetParam().y;
  scene.yaw = GetParam().yaw;
  scene.seed = static_cast<unsigned>(1000 * (scene.x + 3) + 10 * (scene.y + 3));
  // Half the goal's resolution (640 x 512): still within the goal's 15 mm and 0.5 degrees.
  expect_pose(detect(scene, scene.marker, render(scene)), scene, 0.015, 0.5 * kDegree);
}

INSTANTIATE_TEST_SUITE_P(AreaAndHeadings, SquareDetectorPoses,
                         testing::Values(Placement{0, 0, 0}, Placement{1.5, -1.2, 2.0}, Placement{-1.8, 1.9, -2.5},
                                         Placement{2.0, 2.0, 1.0}, Placement{-2.0, -2.0, 3.1},
                                         Placement{0.7, 1.3, -1.0}, Placement{-0.4, -1.7, 0.5 * std::numbers::pi}));

// A tilting robot (dof 6): rocked up to 5 degrees in roll and pitch over the area, the full pose
// comes out, tilt included.
TEST(SquareDetector, FindsTheFullPoseOfATiltingRobot) {
  struct Tilted {
    double x, y, yaw, roll, pitch;
  };
  std::uint32_t merged = 0;
  for (const Tilted& placement : {Tilted{0, 0, 0, 3, -2}, Tilted{1.5, -1.2, 2.0, -5, 1}, Tilted{-1.8, 1.9, -2.5, 2, 5},
                                  Tilted{2.0, 2.0, 1.0, -4, -4}, Tilted{-0.4, -1.7, 1.6, 5, 0}}) {
    TapeScene scene;
    scene.x = placement.x;
    scene.y = placement.y;
    scene.yaw = placement.yaw;
    scene.roll = placement.roll * kDegree;
    scene.pitch = placement.pitch * kDegree;
    scene.seed = static_cast<unsigned>(1000 * (scene.x + 3) + 10 * (scene.y + 3));
    const Rendered frames = render(scene);
    SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::full6, scene.marker, SquareConfig{});
    const SquareDetection detection =
        detector.detect(ImageView8(frames.on.view()), ImageView8(frames.off.view()), noise_of(frames));
    ASSERT_TRUE(detection.found()) << to_string(detection.outcome) << " at " << placement.x << ", " << placement.y;
    const RigidTransform& pose = detection.world_from_base;
    const RollPitchYaw rpy = rpy_from_rotation(pose.rotation);
    std::printf("tilt %+.0f/%+.0f deg: position error %.1f mm, z %.1f mm, roll %.3f pitch %.3f yaw %.3f deg off\n",
                placement.roll, placement.pitch, 1e3 * std::hypot(pose.translation.x() - scene.x, pose.translation.y() - scene.y),
                1e3 * pose.translation.z(), (rpy.roll - scene.roll) / kDegree, (rpy.pitch - scene.pitch) / kDegree,
                wrap_angle(rpy.yaw - scene.yaw) / kDegree);
    EXPECT_NEAR(pose.translation.x(), scene.x, 0.015);
    EXPECT_NEAR(pose.translation.y(), scene.y, 0.015);
    EXPECT_NEAR(pose.translation.z(), 0, 0.015);
    EXPECT_NEAR(rpy.roll, scene.roll, 0.5 * kDegree);
    EXPECT_NEAR(rpy.pitch, scene.pitch, 0.5 * kDegree);
    EXPECT_NEAR(wrap_angle(rpy.yaw - scene.yaw), 0, 0.5 * kDegree);
    EXPECT_GT(detection.covariance(3, 3), 0);  // roll and pitch are estimated
    merged += detection.hypotheses_merged;
  }
  // The tilted search's wide tolerances find variants of the square (a weaker line for a side),
  // which are merged into it rather than scored.
  EXPECT_GT(merged, 0u);
}

TEST(SquareDetector, FindsThePoseWithHalfOfAnySideHidden) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.x = 0.6;
  scene.y = -0.8;
  scene.yaw = 0.7;
  const std::vector<Eigen::Vector2d> hits = scene.ceiling_hits();
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  for (int side = 0; side < 4; ++side) {
    for (const double from : {0.0, 1.0}) {  // the first, then the second half
      scene.hidden = {{side, from, from + 1.0}};
      SCOPED_TRACE(testing::Message() << "side " << side << " hidden from " << from);
      Rendered frames;
      scene.render(hits, frames.on, frames.off);
      expect_pose(detector.detect(ImageView8(frames.on.view()), ImageView8(frames.off.view()), noise_of(frames)), scene,
                  0.015, 0.5 * kDegree);
    }
  }
}

TEST(SquareDetector, ReportsNothingWhenTheSolidSideCannotBeTold) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.x = 0.3;
  scene.all_dashed = true;  // four dashed sides: the pose is ambiguous by quarter turns
  EXPECT_EQ(detect(scene, scene.marker, render(scene)).outcome, SquareOutcome::solid_ambiguous);
}

TEST(SquareDetector, ReportsNothingForASquareOfAnotherSize) {
  TapeScene scene;
  const Rendered frames = render(scene);
  // The map says 2.5 m: the 2 m square on the ceiling is not it.
  EXPECT_FALSE(detect(scene, tape_square(0, 0, 0, 2.5), frames).found());
  // 2.08 m passes the search tolerance (dof 3: max_side_error and a tape width, 5.5 %) but not the
  // consistency check (3 %); 2.15 m is not found either.
  EXPECT_EQ(detect(scene, tape_square(0, 0, 0, 2.08), frames).outcome, SquareOutcome::inconsistent);
  EXPECT_FALSE(detect(scene, tape_square(0, 0, 0, 2.15), frames).found());
}

TEST(SquareDetector, ReportsNothingWithMostOfASideHidden) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.hidden = {{2, -0.1, 1.6}};
  EXPECT_FALSE(detect(scene, scene.marker, render(scene)).found());
}

TEST(SquareDetector, ReportsNothingWithoutTape) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.tape_level = 0;
  const SquareDetection detection = detect(scene, scene.marker, render(scene));
  EXPECT_EQ(detection.outcome, SquareOutcome::no_square);
}

TEST(SquareDetector, SixteenBitFramesGiveTheSamePose) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.x = -0.5;
  scene.yaw = -0.3;
  const Rendered frames = render(scene);
  Image16 on(scene.camera.width, scene.camera.height), off(scene.camera.width, scene.camera.height);
  for (int y = 0; y < on.height(); ++y) {
    for (int x = 0; x < on.width(); ++x) {
      on.view().at(x, y) = static_cast<std::uint16_t>(frames.on.view().at(x, y) * 4);
      off.view().at(x, y) = static_cast<std::uint16_t>(frames.off.view().at(x, y) * 4);
    }
  }
  SquareDetector detector(scene.camera, 10, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  const ImageView16 on16(on.view()), off16(off.view());
  expect_pose(detector.detect(on16, off16, shared_noise(on16, off16)), scene, 0.015, 0.5 * kDegree);
}

TEST(SquareDetector, HeightFoundWithFourDegreesOfFreedom) {
  TapeScene scene;
  scene.x = 0.4;
  scene.yaw = 1.1;
  // The base is 0.1 m above the floor: the square looks 5 % larger than at z = 0, within the
  // search's side tolerance, and the similarity fit finds the height.
  scene.mount.translation().z() = 0.4;
  const Rendered frames = render(scene);
  Eigen::Isometry3d assumed_mount = scene.mount;
  assumed_mount.translation().z() = 0.3;
  SquareDetector detector(scene.camera, 8, to_rigid(assumed_mount), Dof::height4, scene.marker, SquareConfig{});
  const SquareDetection detection =
      detector.detect(ImageView8(frames.on.view()), ImageView8(frames.off.view()), noise_of(frames));
  ASSERT_TRUE(detection.found()) << to_string(detection.outcome);
  EXPECT_NEAR(detection.world_from_base.translation.z(), 0.1, 0.01);
  EXPECT_NEAR(detection.world_from_base.translation.x(), 0.4, 0.015);
}

TEST(SquareDetector, RefusesMismatchedFrames) {
  TapeScene scene;
  scene.camera = fisheye(320, 256);
  const Rendered frames = render(scene);
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  Image16 wide(scene.camera.width, scene.camera.height);
  EXPECT_EQ(detector.detect(ImageView8(frames.on.view()), ImageView16(wide.view()), {}).outcome, SquareOutcome::bad_frames);
  EXPECT_EQ(detector.detect(ImageView16(wide.view()), ImageView16(wide.view()), {}).outcome, SquareOutcome::bad_frames);
  const ImageView8 small = ImageView8(frames.on.view()).region(0, 0, 100, 100);
  EXPECT_EQ(detector.detect(small, small, {}).outcome, SquareOutcome::bad_frames);
}

TEST(SquareDetector, DetectAllocatesNothing) {
  TapeScene scene;
  scene.camera = fisheye(400, 320);
  scene.x = 1.0;
  const Rendered frames = render(scene);
  SquareDetector detector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  SquareDetection detection;
  const DifferenceNoise noise = noise_of(frames);
  {
    AllocationCounter counter;
    detection = detector.detect(ImageView8(frames.on.view()), ImageView8(frames.off.view()), noise);
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_TRUE(detection.found());
  EXPECT_EQ(detection.points.points_dropped, 0u);
  // Weak Hough peaks beyond the list's capacity are dropped (and counted): never the sides.
  EXPECT_EQ(detection.hough.peaks, detection.hough.peaks_dropped + kMaxHoughLines);
}

TEST(SquareDetector, RejectsMarkersItCannotUse) {
  const TapeScene scene;
  SquareMarker tilted = scene.marker;
  tilted.corners[2].z() += 0.1;
  EXPECT_THROW(SquareDetector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, tilted, SquareConfig{}), std::invalid_argument);
  SquareMarker kite = scene.marker;
  kite.corners[2].x() += 0.3;
  EXPECT_THROW(SquareDetector(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, kite, SquareConfig{}), std::invalid_argument);
}

}  // namespace
}  // namespace irloc::test

namespace irloc::test {
namespace {

// Random poses, random occlusions of up to two whole sides, sometimes no solid side at all: the
// path may say none, but whatever it reports as found is right (far inside 0.2 m and 5 deg).
TEST(SquareDetector, NeverReportsAGrossError) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> coordinate(-2.2, 2.2), heading(-std::numbers::pi, std::numbers::pi),
      fraction(0, 1);
  int found = 0;
  constexpr int kCases = 14;
  for (int i = 0; i < kCases; ++i) {
    TapeScene scene;
    scene.camera = fisheye(320, 256);
    scene.x = coordinate(rng);
    scene.y = coordinate(rng);
    scene.yaw = heading(rng);
    scene.seed = static_cast<unsigned>(i);
    scene.all_dashed = fraction(rng) < 0.15;
    const int hidden_sides = static_cast<int>(fraction(rng) * 3);  // 0, 1 or 2
    for (int h = 0; h < hidden_sides; ++h) {
      const double length = 2.0 * fraction(rng);
      const double from = (2.0 - length) * fraction(rng);
      scene.hidden.push_back({static_cast<int>(fraction(rng) * 4), from, from + length});
    }
    const SquareDetection detection = detect(scene, scene.marker, render(scene));
    if (!detection.found()) continue;
    ++found;
    SCOPED_TRACE(testing::Message() << "case " << i);
    EXPECT_FALSE(scene.all_dashed);
    const Eigen::Vector3d& t = detection.world_from_base.translation;
    EXPECT_LT(std::hypot(t.x() - scene.x, t.y() - scene.y), 0.05);
    EXPECT_LT(std::abs(wrap_angle(yaw_of(detection.world_from_base) - scene.yaw)), 1 * kDegree);
  }
  EXPECT_GE(found, kCases / 3);  // the test must exercise found poses, not only refusals
}

}  // namespace
}  // namespace irloc::test
