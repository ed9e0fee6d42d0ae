// Outside-in mode through the Localizer: with LocalizerSetup::outside_in set, every frame is a
// pose attempt without an LED-off partner and the poses are the external source's.
#include <gtest/gtest.h>

#include "algo/pipeline/localizer.hpp"
#include "tests/outside_in/outside_in_drive.hpp"

namespace irloc::test {
namespace {

TEST(OutsideInLocalizer, EveryFrameIsAPoseAttemptOfTheExternalSource) {
  const WallCamera camera;
  LocalizerSetup setup;
  setup.camera = camera.intrinsics;
  setup.outside_in.emplace();
  setup.outside_in->floor_reference = floor_reference_of(camera);
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

}  // namespace
}  // namespace irloc::test
