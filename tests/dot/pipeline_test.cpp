// The whole dot path on rendered strobe pairs: Localizer in, pose out.

#include <bit>
#include <cmath>
#include <map>
#include <numbers>

#include <gtest/gtest.h>

#include "algo/markers/dot/dot_marker_source.hpp"
#include "algo/pipeline/localizer.hpp"
#include "tests/dot/dot_scene.hpp"
#include "tests/dot/localizer_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc {
namespace {

using test::Scene;
using test::expect_pose_near;
using test::render;
using test::Rendered;
using test::setup_for;

constexpr double kDegree = std::numbers::pi / 180;

TEST(DotPipeline, OneMarkerGivesThePoseAndItsId) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 1.0, 2.0, 0.3);
  scene.add_marker(marker);
  scene.world_from_base = test::level_pose(1.05, 1.93, 0.4);
  const Rendered frames = render(scene);
  Localizer localizer(setup_for(scene, {marker}));
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off, 7));
  EXPECT_EQ(estimate.seq, 7u);
  EXPECT_EQ(estimate.source, SourceKind::dot);
  EXPECT_EQ(estimate.marker_id, 1782);
  EXPECT_GT(estimate.confidence, 0.5);
  EXPECT_LE(estimate.confidence, 1.0);
  expect_pose_near(estimate, scene.world_from_base, 0.003, 0.3 * kDegree);
  // Every stage was timed.
  ASSERT_GE(localizer.last_stage_times().size(), 5u);
  EXPECT_STREQ(localizer.last_stage_times()[0].name, "front_end");
}

TEST(DotPipeline, SeveralMarkersLampsAndStraysAllowNoAllocation) {
  Scene scene;
  const std::vector<DotMarker> markers = {test::ceiling_marker(1782, 0.0, 0.0, 0.0),
                                          test::ceiling_marker(33, 0.5, 0.3, 1.2),
                                          test::ceiling_marker(2900, -0.4, 0.35, -2.5)};
  for (const DotMarker& marker : markers) scene.add_marker(marker);
  scene.discs.push_back({{0.3, -0.4, 2.6}, 0.15, 60, 220});  // a lamp, bright in both frames
  scene.discs.push_back({{-0.3, -0.3, 2.6}, 0.012, 140, 0});  // a lone stray reflector
  scene.discs.push_back({{0.0, 0.22, 2.6}, 0.03, 140, 0});    // a large glint
  scene.discs.push_back({{0.06, 0.13, 2.6}, 0.01, 140, 0});   // a dot-like stray within link range
  scene.world_from_base = test::level_pose(0.02, 0.05, -0.6);
  const Rendered frames = render(scene);
  Localizer localizer(setup_for(scene, markers));
  const StrobePair pair = test::strobe_pair(frames.on, frames.off);
  localizer.process(pair);  // warm-up: nothing is allocated lazily, but be fair to the counter
  PoseEstimate estimate;
  {
    test::AllocationCounter counter;
    estimate = localizer.process(pair);
    EXPECT_EQ(counter.count(), 0u);
  }
  expect_pose_near(estimate, scene.world_from_base, 0.002, 0.15 * kDegree);
  ASSERT_NE(localizer.find_source<dot::DotMarkerSource>(), nullptr);
  EXPECT_EQ(localizer.find_source<dot::DotMarkerSource>()->last_diagnostics().markers_used, 3u);
  // The central marker names the pose.
  EXPECT_EQ(estimate.marker_id, 1782);
}

TEST(DotPipeline, RaisedRobotUnderDof4) {
  // The base 6 cm above the floor plane: dof 4 finds its height.
  Scene scene;
  const std::vector<DotMarker> markers = {test::ceiling_marker(1782, 0.0, 0.0, 0.0),
                                          test::ceiling_marker(33, 0.5, 0.3, 1.2)};
  for (const DotMarker& marker : markers) scene.add_marker(marker);
  scene.world_from_base = test::level_pose(0.2, 0.1, -1.0);
  scene.world_from_base.translation().z() = 0.06;
  const Rendered frames = render(scene);
  LocalizerSetup setup = setup_for(scene, markers);
  setup.dof = Dof::height4;
  Localizer localizer(setup);
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  ASSERT_TRUE(estimate.ok);
  EXPECT_NEAR(estimate.x, 0.2, 0.003);
  EXPECT_NEAR(estimate.y, 0.1, 0.003);
  EXPECT_NEAR(estimate.z, 0.06, 0.01);
  EXPECT_EQ(estimate.roll, 0.0);
  EXPECT_EQ(estimate.pitch, 0.0);
  EXPECT_NEAR(estimate.yaw, -1.0, 0.3 * kDegree);
}

TEST(DotPipeline, TiltedRobotUnderDof6) {
  // A robot on a 3 deg ramp: the full pose from three markers. (The test renderer draws each dot as
  // a circle at its projected centre, which a 3 deg tilt changes by far less than the tolerances.)
  Scene scene;
  const std::vector<DotMarker> markers = {test::ceiling_marker(1782, 0.0, 0.0, 0.0),
                                          test::ceiling_marker(33, 0.5, 0.3, 1.2),
                                          test::ceiling_marker(2900, -0.4, 0.35, -2.5)};
  for (const DotMarker& marker : markers) scene.add_marker(marker);
  scene.world_from_base.linear() = rotation_from_rpy(0.05, -0.03, 0.7);
  scene.world_from_base.translation() = Eigen::Vector3d(0.1, -0.05, 0.04);
  const Rendered frames = render(scene);
  LocalizerSetup setup = setup_for(scene, markers);
  setup.dof = Dof::full6;
  Localizer localizer(setup);
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  ASSERT_TRUE(estimate.ok);
  EXPECT_NEAR(estimate.x, 0.1, 0.005);
  EXPECT_NEAR(estimate.y, -0.05, 0.005);
  EXPECT_NEAR(estimate.z, 0.04, 0.01);
  EXPECT_NEAR(estimate.roll, 0.05, 0.3 * kDegree);
  EXPECT_NEAR(estimate.pitch, -0.03, 0.3 * kDegree);
  EXPECT_NEAR(estimate.yaw, 0.7, 0.3 * kDegree);
}

TEST(DotPipeline, AnIdMissingFromTheMapIsNeverUsed) {
  Scene scene;
  scene.add_marker(test::ceiling_marker(1782, 0.0, 0.0, 0.0));
  const Rendered frames = render(scene);
  // The map knows a different ID at the same place.
  Localizer localizer(setup_for(scene, {test::ceiling_marker(1783, 0.0, 0.0, 0.0)}));
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  EXPECT_FALSE(estimate.ok);
  EXPECT_EQ(localizer.find_source<dot::DotMarkerSource>()->last_diagnostics().unknown_ids, 1u);
}

// Map building needs every decoded marker's dots: unmapped IDs and markers the pose dropped too.
TEST(DotPipeline, ObservingEveryMarkerReportsUnmappedAndDroppedMarkersButPosesFromTheGoodOnes) {
  Scene scene;
  const DotMarker good = test::ceiling_marker(1782, 0.0, 0.0, 0.0);
  const DotMarker unmapped = test::ceiling_marker(33, 0.5, 0.3, 1.2);
  const DotMarker moved = test::ceiling_marker(2900, -0.4, 0.35, -2.5);
  for (const DotMarker& marker : {good, unmapped, moved}) scene.add_marker(marker);
  scene.world_from_base = test::level_pose(0.1, -0.05, 0.3);
  const Rendered frames = render(scene);
  DotMarker moved_in_map = moved;
  moved_in_map.origin.x() += 0.4;  // the map still has it where it was
  for (const bool every : {false, true}) {
    LocalizerSetup setup = setup_for(scene, {good, moved_in_map});
    setup.dot.observe_every_marker = every;
    Localizer localizer(setup);
    const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
    ASSERT_TRUE(estimate.ok) << every;
    EXPECT_NEAR(estimate.x, 0.1, 0.005);
    EXPECT_NEAR(estimate.y, -0.05, 0.005);
    std::map<int, int> dots;
    for (const PointObservation& observation : localizer.last_results()[0].observations) {
      ++dots[observation.landmark];
      if (observation.landmark == 33) {
        EXPECT_EQ(observation.world, Eigen::Vector3d::Zero());
      }
    }
    const auto cells = [](int id) { return std::popcount(dot::cells_from_id(id)); };
    if (every) {
      EXPECT_EQ(dots, (std::map<int, int>{{1782, cells(1782)}, {33, cells(33)}, {2900, cells(2900)}}));
    } else {
      EXPECT_EQ(dots, (std::map<int, int>{{1782, cells(1782)}}));
    }
  }
}

// Poses 50 ms apart give the track's velocity: the arc through both, at the later pose, in W.
TEST(DotPipeline, TwoRecentPosesGiveTheTracksVelocity) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 1.0, 2.0, 0.3);
  scene.add_marker(marker);
  Localizer localizer(setup_for(scene, {marker}));
  const auto attempt = [&](double x, double y, double yaw, std::int64_t t_ns) {
    scene.world_from_base = test::level_pose(x, y, yaw);
    const Rendered frames = render(scene);
    StrobePair pair = test::strobe_pair(frames.on, frames.off);
    pair.on.t_ns = t_ns;
    return localizer.process(pair);
  };
  const PoseEstimate first = attempt(1.0, 1.9, 0.4, 1'000'000'000);
  ASSERT_TRUE(first.ok);
  EXPECT_FALSE(first.velocity.has_value());  // no pose before it

  // 0.4 m/s along a heading of 0.4 rad for 50 ms, turning at 0.2 rad/s (the chord of that arc).
  const double dt = 0.05;
  const Eigen::Vector3d moved = Eigen::AngleAxisd(0.4 + 0.005, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(0.4 * dt, 0, 0);
  const PoseEstimate second = attempt(1.0 + moved.x(), 1.9 + moved.y(), 0.41, 1'050'000'000);
  ASSERT_TRUE(second.ok);
  ASSERT_TRUE(second.velocity.has_value());
  const Eigen::Vector3d expected = Eigen::AngleAxisd(0.41, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(0.4, 0, 0);
  // The poses are good to a few millimetres and hundredths of a degree: over 50 ms, a few cm/s.
  const PoseVelocity& velocity = *second.velocity;
  EXPECT_NEAR(velocity.world.x(), expected.x(), 0.06);
  EXPECT_NEAR(velocity.world.y(), expected.y(), 0.06);
  EXPECT_NEAR(velocity.world.z(), 0.0, 1e-9);  // dof 3
  EXPECT_NEAR(velocity.yaw_rate, 0.2, 0.05);
  // The two poses' variances over dt^2.
  EXPECT_NEAR(velocity.covariance(0, 0), (first.covariance(0, 0) + second.covariance(0, 0)) / (dt * dt), 1e-12);
  EXPECT_NEAR(velocity.covariance(3, 3), (first.covariance(5, 5) + second.covariance(5, 5)) / (dt * dt), 1e-12);
  EXPECT_NEAR(velocity.covariance(0, 3), (first.covariance(0, 5) + second.covariance(0, 5)) / (dt * dt), 1e-12);

  // A pose long after the last one has no track.
  const PoseEstimate later = attempt(1.1, 1.9, 0.41, 2'050'000'000);
  ASSERT_TRUE(later.ok);
  EXPECT_FALSE(later.velocity.has_value());
}

TEST(DotPipeline, NoLedOffPartnerMeansNoPose) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 0.0, 0.0, 0.0);
  scene.add_marker(marker);
  const Rendered frames = render(scene);
  Localizer localizer(setup_for(scene, {marker}));
  StrobePair pair = test::strobe_pair(frames.on, frames.off);
  pair.off.reset();
  EXPECT_FALSE(localizer.process(pair).ok);
}

TEST(DotPipeline, BelowTheConfidenceFloorIsNone) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 0.0, 0.0, 0.0);
  scene.add_marker(marker);
  const Rendered frames = render(scene);
  LocalizerSetup setup = setup_for(scene, {marker});
  setup.dot.confidence_floor = 0.999999;
  Localizer localizer(setup);
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  EXPECT_FALSE(estimate.ok);
  EXPECT_GT(localizer.find_source<dot::DotMarkerSource>()->last_diagnostics().confidence, 0.5);
}

TEST(DotPipeline, AFaintCodeDotThatTheBlobsMissFailsTheCellTest) {
  // One code dot at a fifth of the brightness: below the blob threshold, so the candidates spell
  // another ID (which is mapped), but the per-cell intensity test sees light where the decoding
  // says empty and refuses the marker rather than report a wrong ID.
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 0.0, 0.0, 0.0);
  scene.add_marker(marker);
  const int faint_cell = dot::cell_index(1, 1);  // weight 0x010
  for (test::Disc& disc : scene.discs) {
    if ((disc.centre_w - dot::cell_in_world(marker, faint_cell)).norm() < 1e-9) disc.on_level = 35;
  }
  const Rendered frames = render(scene);
  LocalizerSetup setup = setup_for(scene, {marker, test::ceiling_marker(1782 - 0x010, 5.0, 5.0, 0.0)});
  setup.dot.threshold = 40;
  Localizer localizer(setup);
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  EXPECT_FALSE(estimate.ok && estimate.marker_id != 1782);
  EXPECT_EQ(localizer.find_source<dot::DotMarkerSource>()->last_diagnostics().low_cell_margin, 1u);
}

TEST(DotPipeline, ClutterOverflowIsReportedNotFatal) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 0.0, 0.0, 0.0);
  scene.add_marker(marker);
  for (int k = 0; k < 400; ++k) {  // a sparkle of 400 specks
    scene.discs.push_back({{-0.9 + 0.09 * (k % 20), -0.7 + 0.07 * (k / 20), 2.6}, 0.006, 200, 0});
  }
  const Rendered frames = render(scene);
  Localizer localizer(setup_for(scene, {marker}));
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  const dot::DotFrameReport& report = localizer.find_source<dot::DotMarkerSource>()->last_diagnostics();
  EXPECT_GT(report.blobs.blobs_dropped + report.candidates.dropped, 0u);
  EXPECT_EQ(report.threshold_doublings, 2u);  // relabelling did not help: bounded, then reported
  EXPECT_FALSE(estimate.ok && estimate.marker_id != 1782);
}

TEST(DotPipeline, ANoiseFloodIsRelabelledAtAHigherThreshold) {
  // A threshold at the noise level floods the blob list; the path doubles it and finds the marker.
  Scene scene;
  scene.noise_sigma = 3.0;
  const DotMarker marker = test::ceiling_marker(1782, 0.0, 0.0, 0.0);
  scene.add_marker(marker);
  const Rendered frames = render(scene);
  LocalizerSetup setup = setup_for(scene, {marker});
  setup.dot.threshold = 5;
  Localizer localizer(setup);
  const PoseEstimate estimate = localizer.process(test::strobe_pair(frames.on, frames.off));
  const dot::DotFrameReport& report = localizer.find_source<dot::DotMarkerSource>()->last_diagnostics();
  EXPECT_GE(report.threshold_doublings, 1u);
  EXPECT_EQ(report.threshold, 5u << report.threshold_doublings);
  EXPECT_TRUE(estimate.ok);
  EXPECT_EQ(estimate.marker_id, 1782);
}

TEST(DotPipeline, TheSharedPassGivesTheStrobeVerdictAndGatesTheSources) {
  Scene scene;
  const DotMarker marker = test::ceiling_marker(1782, 0.2, -0.1, 0.5);
  scene.add_marker(marker);
  const Rendered frames = render(scene);
  Localizer localizer(setup_for(scene, {marker}));

  // A true pair: verified, and the dot source used the shared pass's blobs (no relabelling).
  const PoseEstimate found = localizer.process(test::strobe_pair(frames.on, frames.off), StrobeGate::require_verified);
  EXPECT_EQ(localizer.last_strobe_verdict(), StrobeVerdict::verified);
  EXPECT_TRUE(found.ok);
  EXPECT_EQ(localizer.last_pair_analysis().relabels, 0u);
  EXPECT_EQ(localizer.find_source<dot::DotMarkerSource>()->last_diagnostics().threshold, localizer.last_pair_analysis().threshold);
  EXPECT_GT(localizer.last_pair_analysis().blobs.size(), 0u);

  // The frames swapped (sync lost): swapped; required verified, no source runs.
  const PoseEstimate refused = localizer.process(test::strobe_pair(frames.off, frames.on), StrobeGate::require_verified);
  EXPECT_EQ(localizer.last_strobe_verdict(), StrobeVerdict::swapped);
  EXPECT_FALSE(refused.ok);
  ASSERT_EQ(localizer.last_stage_times().size(), 1u);  // the shared pass only
  EXPECT_STREQ(localizer.last_stage_times()[0].name, "front_end");
  // Only reported: the sources run (and find nothing in the swapped pair).
  EXPECT_FALSE(localizer.process(test::strobe_pair(frames.off, frames.on)).ok);
  EXPECT_EQ(localizer.last_strobe_verdict(), StrobeVerdict::swapped);
  EXPECT_GT(localizer.last_stage_times().size(), 1u);

  // Nothing lit: no contrast. No LED-off frame: no verdict.
  localizer.process(test::strobe_pair(frames.off, frames.off), StrobeGate::require_verified);
  EXPECT_EQ(localizer.last_strobe_verdict(), StrobeVerdict::no_contrast);
  StrobePair unpaired = test::strobe_pair(frames.on, frames.off);
  unpaired.off.reset();
  localizer.process(unpaired, StrobeGate::require_verified);
  EXPECT_FALSE(localizer.last_strobe_verdict().has_value());
}

}  // namespace
}  // namespace irloc
