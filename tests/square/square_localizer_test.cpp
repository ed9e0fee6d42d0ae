// The square path inside the Localizer: the pose row it produces.

#include <gtest/gtest.h>

#include "algo/markers/square/square_marker_source.hpp"
#include "algo/pipeline/localizer.hpp"
#include "tests/square/tape_scene_localizer.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::test {
namespace {

using namespace irloc::square;  // the source under test

TEST(SquareLocalizer, ReportsTheSquarePose) {
  TapeScene scene;
  scene.x = -1.1;
  scene.y = 0.4;
  scene.yaw = 2.5;
  Image8 on, off;
  scene.render(on, off);
  Localizer localizer(setup_for(scene));
  ASSERT_NE(localizer.find_source<SquareMarkerSource>(), nullptr);
  const StrobePair pair = pair_of(on, off);
  PoseEstimate estimate;
  {
    AllocationCounter counter;
    estimate = localizer.process(pair);
    EXPECT_EQ(counter.count(), 0u);
  }
  ASSERT_TRUE(estimate.ok);
  EXPECT_EQ(estimate.seq, 11u);
  EXPECT_EQ(estimate.source, SourceKind::square);
  EXPECT_EQ(estimate.marker_id, -1);
  EXPECT_NEAR(estimate.x, -1.1, 0.015);
  EXPECT_NEAR(estimate.y, 0.4, 0.015);
  EXPECT_NEAR(wrap_angle(estimate.yaw - 2.5), 0, 0.01);
  EXPECT_EQ(estimate.z, 0);
  EXPECT_EQ(estimate.roll, 0);
  EXPECT_EQ(estimate.pitch, 0);
  EXPECT_GT(estimate.confidence, 0);
}

// The tape mask is built from the Localizer's one pass over the pair when that pass is at the tape
// threshold (the defaults: both median + 5 sigma of the difference), with the pose of the
// detector's own pass; a square threshold of its own makes the detector read the pair again.
TEST(SquareLocalizer, TheTapeMaskComesFromTheSharedPass) {
  TapeScene scene;
  scene.x = 0.7;
  scene.y = -1.3;
  scene.yaw = -0.8;
  Image8 on, off;
  scene.render(on, off);
  const StrobePair pair = pair_of(on, off);
  Localizer localizer(setup_for(scene));
  ASSERT_TRUE(localizer.process(pair).ok);
  const SquareDetection& shared = localizer.find_source<SquareMarkerSource>()->last_diagnostics();
  EXPECT_TRUE(shared.mask_from_shared_pass);
  SquareDetector alone(scene.camera, 8, to_rigid(scene.mount), Dof::planar3, scene.marker, SquareConfig{});
  const SquareDetection own = alone.detect(ImageView8(on.view()), ImageView8(off.view()),
                                           shared_noise(ImageView8(on.view()), ImageView8(off.view())));
  ASSERT_TRUE(own.found());
  EXPECT_FALSE(own.mask_from_shared_pass);
  EXPECT_EQ(own.threshold, shared.threshold);
  EXPECT_EQ(own.points.points, shared.points.points);
  EXPECT_EQ(own.world_from_base.translation, shared.world_from_base.translation);

  LocalizerSetup fixed = setup_for(scene);
  fixed.square.threshold = static_cast<std::uint16_t>(shared.threshold + 10);
  Localizer own_pass(fixed);
  ASSERT_TRUE(own_pass.process(pair).ok);
  EXPECT_FALSE(own_pass.find_source<SquareMarkerSource>()->last_diagnostics().mask_from_shared_pass);
}

TEST(SquareLocalizer, NoPartnerFrameNoPose) {
  TapeScene scene;
  Image8 on, off;
  scene.render(on, off);
  Localizer localizer(setup_for(scene));
  StrobePair pair = pair_of(on, off);
  pair.off.reset();
  const PoseEstimate estimate = localizer.process(pair);
  EXPECT_FALSE(estimate.ok);
  EXPECT_EQ(estimate.source, SourceKind::square);
}

TEST(SquareLocalizer, OneSourceForSeveralSquaresAtAnyDof) {
  const TapeScene scene;
  LocalizerSetup six = setup_for(scene);
  six.dof = Dof::full6;
  EXPECT_NE(Localizer(six).find_source<SquareMarkerSource>(), nullptr);
  LocalizerSetup two = setup_for(scene);
  two.map.square_markers.push_back(tape_square(5, 0, 0));
  const Localizer localizer(two);
  ASSERT_NE(localizer.find_source<SquareMarkerSource>(), nullptr);
  EXPECT_EQ(localizer.find_source<SquareMarkerSource>()->detector().markers().size(), 2u);
}

TEST(SquareLocalizer, TheLastPoseIdentifiesASquareOfASharedPattern) {
  // a1 and a2 share a pattern, b is the only one of its own, beside a1: the first pair gets its
  // pose from b alone, the next one (its prior that pose) identifies a1 too and fuses both.
  SquareMarker a1 = tape_square(-1.2, 0, 0), a2 = tape_square(-1.2, 8, 0), b = tape_square(1.2, 0, 0);
  a1.name = "a1";
  a2.name = "a2";
  b.name = "b";
  b.dash = 0.20;
  TapeScene scene;
  scene.camera = fisheye(480, 384);
  scene.marker = a1;
  scene.other_squares = {a2, b};
  scene.x = 0.1;
  scene.y = -0.1;
  scene.yaw = 0.4;
  Image8 on, off;
  scene.render(on, off);
  LocalizerSetup setup = setup_for(scene);
  setup.map.square_markers = {a1, a2, b};
  Localizer localizer(setup);
  const SquareMarkerSource& source = *localizer.find_source<SquareMarkerSource>();
  StrobePair pair = pair_of(on, off);
  const PoseEstimate first = localizer.process(pair);
  ASSERT_TRUE(first.ok);
  ASSERT_EQ(source.last_diagnostics().square_count, 1u);
  EXPECT_EQ(source.last_diagnostics().squares[0], 2);
  pair.on.t_ns += 100'000'000;
  const PoseEstimate second = localizer.process(pair);
  ASSERT_TRUE(second.ok);
  ASSERT_EQ(source.last_diagnostics().square_count, 2u);
  EXPECT_EQ(source.last_diagnostics().squares[0] + source.last_diagnostics().squares[1], 2);  // a1 (0) and b (2)
  EXPECT_EQ(localizer.last_results()[0].observations.size(), 8u);
  EXPECT_NEAR(second.x, 0.1, 0.015);
  EXPECT_NEAR(second.y, -0.1, 0.015);
}

}  // namespace
}  // namespace irloc::test
