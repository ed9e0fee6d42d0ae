// Outside-in mode through the Localizer: with LocalizerSetup::outside_in set, every frame is a
// pose attempt without an LED-off partner and the poses are the external source's.
#include <gtest/gtest.h>

#include "algo/pipeline/localizer.hpp"
#include "tests/outside_in/outside_in_drive.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::test {
namespace {

using namespace irloc::outside_in;  // the source under test

// Outside-in mode with the tests' wall camera.
LocalizerSetup wall_camera_setup(const WallCamera& camera) {
  LocalizerSetup setup;
  setup.camera = camera.intrinsics;
  setup.outside_in.emplace();
  setup.outside_in->floor_reference = floor_reference_of(camera);
  return setup;
}

TEST(OutsideInLocalizer, EveryFrameIsAPoseAttemptOfTheExternalSource) {
  const WallCamera camera;
  const LocalizerSetup setup = wall_camera_setup(camera);
  Localizer localizer(setup);
  SceneRenderer renderer(camera);
  int poses = 0;
  for (int i = 0; i < 30; ++i) {
    SceneState scene;
    scene.robot = FloorPose{3.5, -2.6 + 0.1 * i, std::numbers::pi / 2};
    FrameTruth truth;
    const auto& pixels = renderer.render(scene, truth);
    const PoseEstimate estimate = localizer.process(
        StrobePair{Frame{std::uint64_t(i), std::int64_t(i) * 100'000'000, false, ImageView8(pixels.data(), 640, 480)},
                   std::nullopt});
    EXPECT_EQ(estimate.source, SourceKind::external);
    if (!estimate.ok) continue;
    ++poses;
    EXPECT_TRUE(truth.robot_whole_in_view);
    EXPECT_NEAR(estimate.x, scene.robot->x, 0.02);
    EXPECT_NEAR(estimate.y, scene.robot->y, 0.02);
    EXPECT_NEAR(std::remainder(estimate.yaw - scene.robot->yaw, 2 * std::numbers::pi), 0, 0.05);
    EXPECT_GT(estimate.covariance(0, 0), 0);
  }
  EXPECT_GE(poses, 15);
}

// `frames` frames of the robot driving across the floor from `start_y`, rendered once.
std::vector<std::vector<std::uint8_t>> drive_frames(SceneRenderer& renderer, double start_y, int frames) {
  std::vector<std::vector<std::uint8_t>> rendered;
  for (int i = 0; i < frames; ++i) {
    SceneState scene;
    scene.robot = FloorPose{3.5, start_y + 0.1 * i, std::numbers::pi / 2};
    FrameTruth truth;
    const auto& pixels = renderer.render(scene, truth);
    rendered.emplace_back(pixels.begin(), pixels.end());
  }
  return rendered;
}

// The estimates of the frames, the first at t = 0, 10 per second.
std::vector<PoseEstimate> replay(Localizer& localizer, const std::vector<std::vector<std::uint8_t>>& frames) {
  std::vector<PoseEstimate> estimates;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    estimates.push_back(localizer.process(StrobePair{
        Frame{std::uint64_t(i), std::int64_t(i) * 100'000'000, false, ImageView8(frames[i].data(), 640, 480)}, std::nullopt}));
  }
  return estimates;
}

bool same(const PoseEstimate& a, const PoseEstimate& b) {
  return a.ok == b.ok && a.x == b.x && a.y == b.y && a.yaw == b.yaw && a.covariance == b.covariance;
}

TEST(OutsideInLocalizer, RestartForgetsTheBackgroundAndTheTrack) {
  const WallCamera camera;
  const LocalizerSetup setup = wall_camera_setup(camera);
  SceneRenderer renderer(camera);
  const auto first = drive_frames(renderer, -2.6, 20), second = drive_frames(renderer, -1.0, 15);
  Localizer fresh(setup), restarted(setup), carried_on(setup);
  replay(restarted, first);
  replay(carried_on, first);
  {
    AllocationCounter counter;
    restarted.restart();
    EXPECT_EQ(counter.count(), 0u);
  }
  const std::vector<PoseEstimate> expected = replay(fresh, second);
  const std::vector<PoseEstimate> after_restart = replay(restarted, second);
  const std::vector<PoseEstimate> without_restart = replay(carried_on, second);
  int posed = 0, differ_without = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_TRUE(same(after_restart[i], expected[i])) << "frame " << i;
    posed += expected[i].ok ? 1 : 0;
    differ_without += same(without_restart[i], expected[i]) ? 0 : 1;
  }
  EXPECT_GE(posed, 4);
  // What the restart forgets matters: the background learnt on the first drive (with the robot
  // in it) changes what the second drive gives.
  EXPECT_GT(differ_without, 0);
}

}  // namespace
}  // namespace irloc::test
