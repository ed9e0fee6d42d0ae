// bench_led_goal's failures on the scene family in small: each a few strobe pairs of the failing
// drive, drawn by the family's generator and rendered, through a fresh source.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "algo/geometry/pose_refinement.hpp"
#include "algo/geometry/camera_model.hpp"
#include "algo/markers/led/led_association.hpp"
#include "algo/markers/led/led_landmark_source.hpp"
#include "host_sim/render/led_family_frames.hpp"
#include "host_sim/scenario/led_scene_family.hpp"

namespace irloc::led {
namespace {

// Each observation of the result names the LED whose true projection its detection is.
void expect_named_right(const SourceResult& result, const LedMatchList& truth, const LedDetectionList& detections) {
  for (const PointObservation& observation : result.observations) {
    EXPECT_TRUE(std::any_of(truth.begin(), truth.end(), [&](const LedMatch& match) {
      return match.landmark == observation.landmark &&
             (detections[static_cast<std::size_t>(match.detection)].pixel - observation.pixel).norm() < 1e-9;
    })) << "LED " << observation.landmark << " associated otherwise";
  }
}

// Two walls under dof 3, scene 0 (seed 2026): at attempts 5 and 6 the renderer vouches for one LED
// (its noise-free peak reaches 1.3 x the threshold); a spurious always-on point is in view too,
// and two more LEDs, faint and far, which the detector measures. Among the level two-point
// solutions of the vouched LED and the spurious point against the 42 ordered pairs of the 7
// mapped LEDs, one puts two LEDs on the two spots at a plausible height, looking away from the
// corner 3.6 m from the truth, and predicts no other LED: only chance stands behind such a pose,
// so a searched pose needs an LED beyond its minimal set (confirmation).
TEST(LedFamilyCases, OneLedAndASpuriousPointAreUnconfirmed) {
  const sim::LedFamilyScene scene = sim::draw_led_family_scene(2026, sim::LedFamilyClass::two_walls_dof3, 0);
  ASSERT_TRUE(std::any_of(scene.clutter.begin(), scene.clutter.end(),
                          [](const sim::LedClutter& c) { return c.kind == sim::LedClutter::Kind::spurious; }));
  const LedSourceConfig config;
  const SourceSetup setup{scene.camera, scene.mount, scene.dof, scene.map, scene.bit_depth};
  const CameraModel camera(scene.camera);
  sim::LedFamilyPair pair;
  for (const int attempt : {5, 6}) {
    LedLandmarkSource source(setup, config);  // no track: the search decides
    sim::render_led_family_pair(scene, attempt, config.threshold, pair);
    ASSERT_EQ(pair.visible.size(), 1u);
    SourceResult result;
    source.process(SourceInput{pair.on, &pair.off}, result);
    // The whole frame: the faint LEDs confirm the true pose (each observation naming the LED at
    // its pixel), or there is no pose.
    const LedMatchList truth = sim::true_association(pair, source.last_diagnostics().detections, 2);
    if (result.ok) {
      EXPECT_LT((result.world_from_base.translation - pair.world_from_base.translation).norm(), 0.05);
      expect_named_right(result, truth, source.last_diagnostics().detections);
    }
    // The vouched LED and the spurious point alone (the faint LEDs' detections left out).
    LedDetectionList detections;
    StaticVector<Eigen::Vector3d, kMaxLedDetections> bearings;
    for (std::size_t d = 0; d < source.last_diagnostics().detections.size(); ++d) {
      const auto faint = std::find_if(truth.begin(), truth.end(), [&](const LedMatch& match) {
        return match.detection == static_cast<int>(d) && match.landmark != pair.visible[0].landmark;
      });
      if (faint != truth.end()) continue;
      detections.push_back(source.last_diagnostics().detections[d]);
      Eigen::Vector3d bearing;
      ASSERT_TRUE(camera.unproject(detections.back().pixel, bearing));
      bearings.push_back(bearing);
    }
    ASSERT_EQ(detections.size(), 2u);
    LedAssociator associator(camera, scene.mount, scene.dof, scene.map, config);
    LedAssociation association;
    associator.search(detections, bearings, association);
    EXPECT_FALSE(association.ok) << "a pose "
                                 << (association.fit.world_from_base.translation - pair.world_from_base.translation).norm()
                                 << " m from the truth";
    EXPECT_EQ(association.outcome, LedOutcome::unconfirmed);
  }
}

// Ceiling under dof 3, scene 51 (seed 29), attempt 0: four LEDs detected through a fisheye, each
// 1.1 to 1.8 times the detection threshold; the true pose predicts two more lit LEDs well inside
// the image and their cones, away from any glare, too faint to be detected. Counted missing, the
// two refuted the true pose (`no association`). An unseen LED is missing only where the faintest
// matched LED, moved to its range, would show led.missing_brightness times the threshold: where
// the LEDs seen are that faint, one at their range may or may not be seen.
TEST(LedFamilyCases, FaintLedsDoNotMakeAnUnseenOneMissing) {
  const sim::LedFamilyScene scene = sim::draw_led_family_scene(29, sim::LedFamilyClass::ceiling_dof3, 51);
  const SourceSetup setup{scene.camera, scene.mount, scene.dof, scene.map, scene.bit_depth};
  const LedSourceConfig config;
  sim::LedFamilyPair pair;
  sim::render_led_family_pair(scene, 0, config.threshold, pair);
  LedLandmarkSource source(setup, config);  // no track: the search decides
  SourceResult result;
  source.process(SourceInput{pair.on, &pair.off}, result);
  ASSERT_TRUE(result.ok) << result.outcome;
  EXPECT_LT((result.world_from_base.translation - pair.world_from_base.translation).norm(), 0.05);
  const LedMatchList truth = sim::true_association(pair, source.last_diagnostics().detections, 2);
  EXPECT_EQ(result.observations.size(), truth.size());
  expect_named_right(result, truth, source.last_diagnostics().detections);
  LedSourceConfig every_unseen_missing = config;  // the rule before
  every_unseen_missing.missing_brightness = 0;
  LedLandmarkSource before(setup, every_unseen_missing);
  SourceResult refused;
  before.process(SourceInput{pair.on, &pair.off}, refused);
  EXPECT_FALSE(refused.ok) << "the case is gone";
}

// Wall under dof 4, scene 25 (seed 41), attempts 1, 4, 8 and 9: three LEDs and a spurious point
// detected; four more lit LEDs lie inside a window's glare, whose spot the detector refuses as too
// large. Counted missing, they refuted the true pose (`no association`); in glare an LED is hidden,
// not missing.
TEST(LedFamilyCases, LedsInAWindowsGlareAreNotMissing) {
  const sim::LedFamilyScene scene = sim::draw_led_family_scene(41, sim::LedFamilyClass::wall_dof4, 25);
  const LedSourceConfig config;
  const SourceSetup setup{scene.camera, scene.mount, scene.dof, scene.map, scene.bit_depth};
  sim::LedFamilyPair pair;
  for (const int attempt : {1, 4, 8, 9}) {
    LedLandmarkSource source(setup, config);  // no track: the search decides
    sim::render_led_family_pair(scene, attempt, config.threshold, pair);
    SourceResult result;
    source.process(SourceInput{pair.on, &pair.off}, result);
    const LedDiagnostics seen = source.last_diagnostics();
    ASSERT_EQ(seen.glare.size(), 1u) << "attempt " << attempt;
    const int in_glare = static_cast<int>(std::count_if(pair.lit.begin(), pair.lit.end(), [&](const sim::VisibleLed& led) {
      return seen.glare[0].contains(led.pixel);
    }));
    EXPECT_GE(in_glare, 3) << "attempt " << attempt << ": the case is gone";
    ASSERT_TRUE(result.ok) << "attempt " << attempt << ": " << result.outcome;
    EXPECT_LT((result.world_from_base.translation - pair.world_from_base.translation).norm(), 0.05);
    const LedMatchList truth = sim::true_association(pair, seen.detections, 2);
    EXPECT_EQ(result.observations.size(), truth.size());
    expect_named_right(result, truth, seen.detections);
  }
}

// A dead LED and a mirrored pose (seed 29): two walls under dof 3, scene 13, attempt 1, and a flat
// cluster under dof 6, scene 61, attempt 9. The true pose predicts the dead LED and counts it
// missing; a mirrored pose matches as many LEDs and puts the dead one outside its cone (3.7 m and
// 1.5 m from the truth). Fewer missing LEDs alone must not decide between them.
TEST(LedFamilyCases, ADeadLedDoesNotTipAMirroredPose) {
  struct Case {
    sim::LedFamilyClass family_class;
    int scene, attempt;
  };
  for (const Case& c : {Case{sim::LedFamilyClass::two_walls_dof3, 13, 1}, Case{sim::LedFamilyClass::clustered_dof6, 61, 9}}) {
    const sim::LedFamilyScene scene = sim::draw_led_family_scene(29, c.family_class, c.scene);
    const LedSourceConfig config;
    const SourceSetup setup{scene.camera, scene.mount, scene.dof, scene.map, scene.bit_depth};
    sim::LedFamilyPair pair;
    sim::render_led_family_pair(scene, c.attempt, config.threshold, pair);
    LedLandmarkSource source(setup, config);  // no track: the search decides
    SourceResult result;
    source.process(SourceInput{pair.on, &pair.off}, result);
    if (result.ok) {
      EXPECT_LT((result.world_from_base.translation - pair.world_from_base.translation).norm(), 0.1)
          << "scene " << c.scene << " attempt " << c.attempt;
    }
  }
}

// bench_led_goal's "gross errors" on seed 29, wall under dof 6, scene 269 (attempts 1, 5, 7, 8):
// five LEDs 7.6 m ahead, nearly level, 2.9 m across, through a fisheye of f 320 px, so 8.6 px
// apart in pairs. The renderer vouches for one of them as visible (it calls spots closer than
// 6 px + 3 sigma merged), so the benchmark had no least-squares fit told the true association to
// compare with and judged the 0.21 m height error by the bare 0.1 m. The detector measures all
// five; the source's pose is that fit's (right association, same minimum), and its covariance
// says the height is undetermined there (sigma about 2.7 m at 0.2 px of centre noise): under
// dof 6 height and pitch trade off, while x, y and yaw hold.
TEST(LedFamilyCases, FarLevelLedsLeaveTheHeightToTheCovariance) {
  const sim::LedFamilyScene scene = sim::draw_led_family_scene(29, sim::LedFamilyClass::wall_dof6, 269);
  const LedSourceConfig config;
  const SourceSetup setup{scene.camera, scene.mount, scene.dof, scene.map, scene.bit_depth};
  sim::LedFamilyPair pair;
  sim::render_led_family_pair(scene, 7, config.threshold, pair);
  ASSERT_EQ(pair.visible.size(), 1u);
  LedLandmarkSource source(setup, config);
  SourceResult result;
  source.process(SourceInput{pair.on, &pair.off}, result);
  ASSERT_TRUE(result.ok) << result.outcome;

  // The least-squares fit told the true association, from the truth.
  const LedMatchList truth_matches = sim::true_association(pair, source.last_diagnostics().detections, 2);
  ASSERT_EQ(truth_matches.size(), 5u);
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
  for (const LedMatch& match : truth_matches) {
    world.push_back(scene.map.led_landmarks[static_cast<std::size_t>(match.landmark)].position);
    pixels.push_back(source.last_diagnostics().detections[static_cast<std::size_t>(match.detection)].pixel);
    EXPECT_TRUE(std::any_of(result.observations.begin(), result.observations.end(), [&](const PointObservation& o) {
      return o.landmark == match.landmark && (o.pixel - pixels.back()).norm() < 1e-9;
    })) << "LED " << match.landmark << " associated otherwise";
  }
  RefinementOptions options;
  options.dof = scene.dof;
  options.loss_scale_px = config.loss_scale_px;
  options.pixel_sigma = config.pixel_sigma;
  const PoseFit baseline =
      refine_pose(world, pixels, CameraModel(scene.camera), scene.mount, pair.world_from_base, options);
  ASSERT_TRUE(baseline.ok);
  EXPECT_LT((result.world_from_base.translation - baseline.world_from_base.translation).norm(), 0.01);

  const Eigen::Vector3d error = result.world_from_base.translation - pair.world_from_base.translation;
  EXPECT_LT(error.head<2>().norm(), 0.05);
  EXPECT_GT(std::abs(error.z()), 0.1);  // the case: the height is off
  EXPECT_GT(std::sqrt(result.covariance(2, 2)), 5 * std::abs(error.z()));  // and the covariance says it may be
}

}  // namespace
}  // namespace irloc::led
