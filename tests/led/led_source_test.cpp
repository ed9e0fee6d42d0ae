// The LED landmark source end to end on simulator-rendered strobe pairs: the goal scene under dof
// 6, the dof 3 and 4 cases, and the scenes that could fool an association without IDs (a regular
// row, a missing LED, a spurious bright point, a lamp beside an LED), which must never give a
// wrong pose; tracking; no allocation per frame; the covariance against the spread of the poses.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "algo/markers/led/led_landmark_source.hpp"
#include "algo/pipeline/localizer.hpp"
#include "tests/led/led_scene.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::led {
namespace {

using test::LedScene;
using test::led_at;
using test::render_pair;
using test::RenderedPair;

// Five LEDs on a wall 4 m ahead at different heights (the goal scene).
std::vector<LedLandmark> wall_leds() {
  return {led_at(4.0, -1.2, 0.9), led_at(4.0, -0.4, 1.4), led_at(4.0, 0.5, 0.7), led_at(4.0, 1.3, 1.2),
          led_at(4.0, 0.1, 1.7)};
}

LedScene goal_scene() {
  LedScene scene;
  scene.scene_leds = wall_leds();
  scene.base_xyz = {0.3, -0.2, 0.02};
  scene.yaw = 0.06;
  scene.roll = 0.03;
  scene.pitch = -0.04;
  return scene;
}

struct Attempt {
  SourceResult result;
  RigidTransform truth;
};

// A source over one map, fed rendered pairs.
class Harness {
 public:
  Harness(const LedScene& scene, std::vector<LedLandmark> map_leds, Dof dof, const LedSourceConfig& config = {})
      : camera_(scene.camera), mount_(scene.mount) {
    map_.led_landmarks = std::move(map_leds);
    source_ = std::make_unique<LedLandmarkSource>(SourceSetup{camera_, mount_, dof, map_, scene.bit_depth}, config);
  }
  void run(const LedScene& scene, Attempt& attempt, std::uint64_t seq = 0) {
    run(scene, test::render_radiance(scene), attempt, seq);
  }
  void run(const LedScene& scene, const test::SceneRadiance& radiance, Attempt& attempt, std::uint64_t seq = 0) {
    expose_pair(scene, radiance, pair_, seq);
    attempt.truth = scene.world_from_base();
    source_->process(SourceInput{pair_.on, &pair_.off}, attempt.result);
  }
  LedLandmarkSource& source() { return *source_; }
  const MarkerMap& map() const { return map_; }

 private:
  CameraIntrinsics camera_;
  RigidTransform mount_;
  MarkerMap map_;
  std::unique_ptr<LedLandmarkSource> source_;
  RenderedPair pair_;
};

double position_error(const Attempt& a) { return (a.result.world_from_base.translation - a.truth.translation).norm(); }
double angle_error(const Attempt& a) {
  const Eigen::Matrix3d difference = a.result.world_from_base.rotation.transpose() * a.truth.rotation;
  return std::acos(std::clamp(0.5 * (difference.trace() - 1), -1.0, 1.0));
}
// "Never a wrong pose": either no pose, or one close to the truth.
void expect_not_wrong(const Attempt& a) {
  if (!a.result.ok) return;
  EXPECT_LT(position_error(a), 0.05);
  EXPECT_LT(angle_error(a), 0.02);
}

TEST(LedSource, GoalSceneDof6) {
  const LedScene scene = goal_scene();
  Harness harness(scene, wall_leds(), Dof::full6);
  Attempt attempt;
  harness.run(scene, attempt);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  EXPECT_EQ(attempt.result.kind, SourceKind::led);
  std::printf("goal scene: position error %.2f mm, angle error %.3f deg, rms %.3f px\n",
              1e3 * position_error(attempt), angle_error(attempt) * 180 / M_PI, attempt.result.rms_px);
  EXPECT_LT(position_error(attempt), 0.015);
  EXPECT_LT(angle_error(attempt), 0.2 * M_PI / 180);
  // One observation per LED, naming the right landmark.
  ASSERT_EQ(attempt.result.observations.size(), 5u);
  for (const PointObservation& o : attempt.result.observations) {
    const auto truth = scene.project(harness.map().led_landmarks[static_cast<std::size_t>(o.landmark)].position);
    ASSERT_TRUE(truth.has_value());
    EXPECT_LT((o.pixel - *truth).norm(), 0.1);
    EXPECT_EQ(o.world, harness.map().led_landmarks[static_cast<std::size_t>(o.landmark)].position);
  }
}

TEST(LedSource, ALocalizerWithAnLedMapGivesLedPoses) {
  const LedScene scene = goal_scene();
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = scene.mount;
  setup.dof = Dof::full6;
  setup.map.led_landmarks = wall_leds();
  Localizer localizer(setup);
  RenderedPair pair;
  render_pair(scene, pair);
  const PoseEstimate estimate = localizer.process(StrobePair{pair.on, pair.off});
  ASSERT_TRUE(estimate.ok);
  EXPECT_EQ(estimate.source, SourceKind::led);
  EXPECT_NEAR(estimate.x, scene.base_xyz.x(), 0.015);
  EXPECT_NEAR(estimate.y, scene.base_xyz.y(), 0.015);
  EXPECT_NEAR(estimate.yaw, scene.yaw, 0.003);
  EXPECT_GT(estimate.covariance(0, 0), 0);
}

TEST(LedSource, SixteenBitFrames) {
  LedScene scene = goal_scene();
  scene.bit_depth = 12;
  Harness harness(scene, wall_leds(), Dof::full6);
  Attempt attempt;
  harness.run(scene, attempt);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  EXPECT_LT(position_error(attempt), 0.015);
}

// Three more attempts, the robot 2 cm and 0.01 rad further each: every one tracked (no search),
// without allocating, within max_position_error of the truth.
void drive_tracked(LedScene& scene, Harness& harness, Attempt& attempt, double max_position_error) {
  for (std::uint64_t seq = 1; seq < 4; ++seq) {
    scene.base_xyz.x() += 0.02;
    scene.yaw += 0.01;
    RenderedPair pair;
    render_pair(scene, pair, seq);
    {
      test::AllocationCounter counter;
      harness.source().process(SourceInput{pair.on, &pair.off}, attempt.result);
      EXPECT_EQ(counter.count(), 0u);
    }
    attempt.truth = scene.world_from_base();
    ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
    EXPECT_EQ(harness.source().last_diagnostics().hypotheses, 0) << "tracked, not searched";
    EXPECT_LT(position_error(attempt), max_position_error);
    EXPECT_LT(angle_error(attempt), 0.02);
  }
}

TEST(LedSource, ThreeLedsUnderDof3And4AndTwoOnlyUnconfirmed) {
  LedScene scene;
  scene.scene_leds = {led_at(4.0, -0.8, 1.5), led_at(4.0, 0.6, 1.0)};
  scene.base_xyz = {0.2, 0.3, 0};
  scene.yaw = -0.1;
  // Two LEDs are the two-point form's minimal set: nothing beyond them tests the association.
  Harness two(scene, scene.scene_leds, Dof::planar3);
  Attempt attempt;
  two.run(scene, attempt);
  EXPECT_FALSE(attempt.result.ok);
  EXPECT_STREQ(attempt.result.outcome, "unconfirmed");

  scene.scene_leds.push_back(led_at(4.5, 1.2, 1.8));
  Harness planar(scene, scene.scene_leds, Dof::planar3);
  planar.run(scene, attempt);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  EXPECT_LT(position_error(attempt), 0.02);
  EXPECT_LT(angle_error(attempt), 0.005);

  scene.base_xyz.z() = 0.05;
  Harness height(scene, scene.scene_leds, Dof::height4);
  height.run(scene, attempt);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  EXPECT_LT(position_error(attempt), 0.02);
  EXPECT_LT(angle_error(attempt), 0.005);
}

TEST(LedSource, ARecentTrackConfirmsASearchedMinimalSet) {
  // Dof 3: three LEDs seen, then a 0.2 rad turn (beyond tracking's pixel gate) takes one out of
  // the image. The search's two-LED pose is the prediction's (the last pose, 67 ms before): a pose.
  // Without a recent pose there, the same view is `unconfirmed`.
  LedScene scene;
  scene.scene_leds = {led_at(4.0, -0.8, 1.5), led_at(4.0, 0.6, 1.0), led_at(4.5, 2.2, 1.8)};
  scene.base_xyz = {0.2, 0.3, 0};
  LedScene turned = scene;
  turned.yaw = -0.2;
  ASSERT_TRUE(scene.project(scene.scene_leds[2].position).has_value());
  ASSERT_FALSE(turned.project(scene.scene_leds[2].position).has_value()) << "the third LED stays in view";
  auto second_view = [&](const LedScene& first, std::uint64_t first_seq, std::uint64_t seq) {
    Harness harness(first, scene.scene_leds, Dof::planar3);
    Attempt attempt;
    harness.run(first, attempt, first_seq);
    EXPECT_TRUE(attempt.result.ok) << attempt.result.outcome;
    harness.run(turned, attempt, seq);
    EXPECT_GT(harness.source().last_diagnostics().hypotheses, 0) << "searched";
    return attempt;
  };
  const Attempt confirmed = second_view(scene, 0, 1);
  ASSERT_TRUE(confirmed.result.ok) << confirmed.result.outcome;
  EXPECT_LT(position_error(confirmed), 0.02);
  EXPECT_LT(angle_error(confirmed), 0.005);
  ASSERT_EQ(confirmed.result.observations.size(), 2u);
  for (const PointObservation& o : confirmed.result.observations) {
    EXPECT_LT((o.pixel - *turned.project(o.world)).norm(), 1.0);
  }
  // The last pose older than track_timeout (0.67 s), or 0.35 m away (within reach, beyond
  // track_max_jump): no pose.
  EXPECT_STREQ(second_view(scene, 0, 10).result.outcome, "unconfirmed");
  LedScene aside = scene;
  aside.base_xyz.y() += 0.35;
  EXPECT_STREQ(second_view(aside, 0, 1).result.outcome, "unconfirmed");
  Harness fresh(turned, scene.scene_leds, Dof::planar3);
  Attempt alone;
  fresh.run(turned, alone, 1);
  EXPECT_STREQ(alone.result.outcome, "unconfirmed");
}

TEST(LedSource, RegularRowIsAmbiguousNeverWrong) {
  // 17 LEDs every 0.5 m at one height: the camera sees a stretch of the row that looks the same
  // from 0.5 m to either side.
  LedScene scene;
  for (int i = -8; i <= 8; ++i) scene.scene_leds.push_back(led_at(4.0, 0.5 * i, 1.2));
  for (const Dof dof : {Dof::planar3, Dof::height4}) {
    Harness harness(scene, scene.scene_leds, dof);
    Attempt attempt;
    harness.run(scene, attempt);
    EXPECT_FALSE(attempt.result.ok) << "a pose from a symmetric row";
    EXPECT_STREQ(attempt.result.outcome, "ambiguous");
    expect_not_wrong(attempt);
  }
}

TEST(LedSource, MissingLedSpuriousPointAndLampNeverGiveAWrongPose) {
  // One mapped LED dark.
  {
    LedScene scene = goal_scene();
    std::vector<LedLandmark> map = wall_leds();
    map.push_back(led_at(4.0, -0.9, 1.6));
    Harness harness(scene, map, Dof::full6);
    Attempt attempt;
    harness.run(scene, attempt);
    EXPECT_TRUE(attempt.result.ok) << attempt.result.outcome;
    expect_not_wrong(attempt);
  }
  // A bright point that is not in the map.
  {
    LedScene scene = goal_scene();
    scene.scene_leds.push_back(led_at(4.0, 0.9, 0.4));
    Harness harness(scene, wall_leds(), Dof::full6);
    Attempt attempt;
    harness.run(scene, attempt);
    EXPECT_TRUE(attempt.result.ok) << attempt.result.outcome;
    expect_not_wrong(attempt);
    EXPECT_EQ(attempt.result.observations.size(), 5u);
  }
  // A lamp right beside an LED.
  {
    LedScene scene = goal_scene();
    const Eigen::Vector2d led = *scene.project(wall_leds()[2].position);
    const int x = static_cast<int>(std::lround(led.x())), y = static_cast<int>(std::lround(led.y()));
    scene.lamps = {{x + 3, y - 2, x + 7, y + 2, 40.0f}};
    Harness harness(scene, wall_leds(), Dof::full6);
    Attempt attempt;
    harness.run(scene, attempt);
    expect_not_wrong(attempt);
  }
}

TEST(LedSource, ADeadLedDoesNotStopTheTrack) {
  // The map holds an LED that never lights. The search allows for it; tracking may miss it again,
  // as the last pose did, and allocates nothing for it.
  LedScene scene = goal_scene();
  std::vector<LedLandmark> map = wall_leds();
  map.push_back(led_at(4.0, -0.9, 1.6));
  Harness harness(scene, map, Dof::full6);
  Attempt attempt;
  harness.run(scene, attempt, 0);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  EXPECT_GT(harness.source().last_diagnostics().hypotheses, 0);
  EXPECT_EQ(harness.source().last_diagnostics().association.missing, 1);
  drive_tracked(scene, harness, attempt, 0.05);
}

TEST(LedSource, RestartEndsTheTrackAndForgetsTheLastPoses) {
  // Six pairs of a slow drive, rendered once: the first four make a track, the last two follow.
  LedScene scene = goal_scene();
  std::vector<std::unique_ptr<RenderedPair>> pairs;
  for (std::uint64_t seq = 0; seq < 6; ++seq) {
    scene.base_xyz.x() += 0.02;
    scene.yaw += 0.01;
    pairs.push_back(std::make_unique<RenderedPair>());
    render_pair(scene, *pairs.back(), seq);
  }
  Harness fresh(scene, wall_leds(), Dof::full6), restarted(scene, wall_leds(), Dof::full6),
      carried_on(scene, wall_leds(), Dof::full6);
  SourceResult result;
  for (std::size_t i = 0; i < 4; ++i) {
    restarted.source().process(SourceInput{pairs[i]->on, &pairs[i]->off}, result);
    carried_on.source().process(SourceInput{pairs[i]->on, &pairs[i]->off}, result);
  }
  {
    test::AllocationCounter counter;
    restarted.source().restart();
    EXPECT_EQ(counter.count(), 0u);
  }
  for (std::size_t i = 4; i < 6; ++i) {
    SourceResult expected, after_restart, without_restart;
    fresh.source().process(SourceInput{pairs[i]->on, &pairs[i]->off}, expected);
    const int searched = fresh.source().last_diagnostics().hypotheses;
    restarted.source().process(SourceInput{pairs[i]->on, &pairs[i]->off}, after_restart);
    carried_on.source().process(SourceInput{pairs[i]->on, &pairs[i]->off}, without_restart);
    ASSERT_TRUE(expected.ok) << expected.outcome;
    if (i == 4) {
      EXPECT_GT(searched, 0) << "a fresh source's first pair is searched";
    }
    EXPECT_EQ(restarted.source().last_diagnostics().hypotheses, searched) << "pair " << i;
    EXPECT_EQ(after_restart.ok, expected.ok);
    EXPECT_EQ(after_restart.world_from_base.translation, expected.world_from_base.translation) << "pair " << i;
    EXPECT_EQ(after_restart.world_from_base.rotation, expected.world_from_base.rotation) << "pair " << i;
    EXPECT_EQ(after_restart.covariance, expected.covariance) << "pair " << i;
    // Without the restart the source tracks on from the first four pairs, as it should.
    EXPECT_EQ(carried_on.source().last_diagnostics().hypotheses, 0) << "pair " << i;
  }
}

TEST(LedSource, TooUncertainJudgesTheHorizontalPositionAndYaw) {
  // On one wall under dof 6 height and pitch trade off: the 3-D position sigma is dominated by z,
  // which the robot does not use. The gate compares the x-y sigma and the yaw sigma.
  const LedScene scene = goal_scene();
  Attempt attempt;
  Harness reference(scene, wall_leds(), Dof::full6);
  reference.run(scene, attempt);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  const Eigen::Matrix<double, 6, 6>& covariance = attempt.result.covariance;
  const double horizontal = std::sqrt(covariance(0, 0) + covariance(1, 1));
  const double full = std::sqrt(covariance.topLeftCorner<3, 3>().trace());
  const double yaw = std::sqrt(covariance(5, 5));
  ASSERT_GT(full, 1.2 * horizontal) << "the scene no longer shows the height's weakness";

  LedSourceConfig config;
  config.max_position_sigma = 0.5 * (horizontal + full);  // the 3-D sigma would refuse it
  Harness between(scene, wall_leds(), Dof::full6, config);
  between.run(scene, attempt);
  EXPECT_TRUE(attempt.result.ok) << attempt.result.outcome;

  config.max_position_sigma = 0.9 * horizontal;
  Harness below(scene, wall_leds(), Dof::full6, config);
  below.run(scene, attempt);
  EXPECT_FALSE(attempt.result.ok);
  EXPECT_STREQ(attempt.result.outcome, "too uncertain");

  config = LedSourceConfig{};
  config.max_yaw_sigma = 0.9 * yaw;
  Harness yaw_below(scene, wall_leds(), Dof::full6, config);
  yaw_below.run(scene, attempt);
  EXPECT_FALSE(attempt.result.ok);
  EXPECT_STREQ(attempt.result.outcome, "too uncertain");
}

TEST(LedSource, ASearchedPoseTheRobotCannotHaveReachedIsRefused) {
  // A metre sideways one attempt (67 ms) after the last pose: beyond the fastest robot's reach
  // (robot.max_speed); once the last pose is older than reach_window the same view gives its pose.
  LedScene scene = goal_scene();
  Harness harness(scene, wall_leds(), Dof::full6);
  Attempt attempt;
  harness.run(scene, attempt, 0);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  scene.base_xyz.y() += 1.0;
  harness.run(scene, attempt, 1);
  EXPECT_FALSE(attempt.result.ok);
  EXPECT_STREQ(attempt.result.outcome, "out of reach");
  harness.run(scene, attempt, 40);
  ASSERT_TRUE(attempt.result.ok) << attempt.result.outcome;
  expect_not_wrong(attempt);
}

TEST(LedSource, TracksFromTheLastPoseAndAllocatesNothing) {
  LedScene scene = goal_scene();
  Harness harness(scene, wall_leds(), Dof::full6);
  Attempt attempt;
  harness.run(scene, attempt, 0);  // warms up
  ASSERT_TRUE(attempt.result.ok);
  EXPECT_GT(harness.source().last_diagnostics().hypotheses, 0);
  drive_tracked(scene, harness, attempt, 0.015);
  // The search allocates nothing either (a track older than track_timeout = 0 is never used).
  LedSourceConfig no_tracking;
  no_tracking.track_timeout = 0;
  Harness searching(scene, wall_leds(), Dof::full6, no_tracking);
  searching.run(scene, attempt, 10);
  RenderedPair pair;
  render_pair(scene, pair, 11);
  {
    test::AllocationCounter counter;
    searching.source().process(SourceInput{pair.on, &pair.off}, attempt.result);
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_TRUE(attempt.result.ok);
  EXPECT_GT(searching.source().last_diagnostics().hypotheses, 0);
}

TEST(LedSource, CovarianceShowsTheHeightPitchCorrelationAndMatchesTheSpread) {
  LedSourceConfig config;
  const int runs = 16;
  std::vector<SourceResult> results(runs);
  double sum_squared_pixel_error = 0;
  int pixel_errors = 0;
  LedScene scene = goal_scene();
  const RigidTransform truth = scene.world_from_base();
  const test::SceneRadiance radiance = test::render_radiance(scene);  // one render, many noise draws
  for (int run = 0; run < runs; ++run) {
    scene.seed = 100 + static_cast<std::uint64_t>(run);
    Harness harness(scene, wall_leds(), Dof::full6, config);
    Attempt attempt;
    harness.run(scene, radiance, attempt);
    ASSERT_TRUE(attempt.result.ok);
    results[static_cast<std::size_t>(run)] = attempt.result;
    for (const PointObservation& o : attempt.result.observations) {
      sum_squared_pixel_error += (o.pixel - *scene.project(o.world)).squaredNorm();
      pixel_errors += 2;
    }
  }
  const PoseCovariance& covariance = results[0].covariance;
  const double correlation = covariance(2, 4) / std::sqrt(covariance(2, 2) * covariance(4, 4));
  std::printf("z-pitch correlation %.5f\n", correlation);
  EXPECT_GT(std::abs(correlation), 0.8);

  // The covariance scaled to the centres' measured noise against the poses' spread.
  const double pixel_sigma = std::sqrt(sum_squared_pixel_error / pixel_errors);
  const double scale = pixel_sigma / config.pixel_sigma;
  const PoseParameters truth_parameters = parameters_from_pose(truth);
  for (const int parameter : {0, 1, 2, 5}) {
    double sum = 0;
    for (const SourceResult& r : results) {
      sum += std::pow(parameters_from_pose(r.world_from_base)[parameter] - truth_parameters[parameter], 2);
    }
    const double measured = std::sqrt(sum / runs);
    const double predicted = scale * std::sqrt(covariance(parameter, parameter));
    std::printf("parameter %d: predicted %.3g, measured %.3g (pixel sigma %.3f)\n", parameter, predicted, measured,
                pixel_sigma);
    EXPECT_GT(measured, predicted / 3);
    EXPECT_LT(measured, predicted * 3);
  }
}

}  // namespace
}  // namespace irloc::led
