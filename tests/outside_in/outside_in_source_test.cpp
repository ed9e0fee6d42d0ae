// The outside-in source on rendered wall-camera scenes (host_sim/render/outside_in_renderer.hpp), whose ray caster
// and truth are independent of the source's own box geometry.
#include "algo/markers/outside_in/outside_in_source.hpp"

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "tests/outside_in/outside_goal_rooms.hpp"
#include "tests/outside_in/outside_in_drive.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::test {
namespace {

using namespace irloc::outside_in;  // the source under test

constexpr double kFps = 10;

// The analytic silhouette moments against the ray-cast mask of the box alone.
// A pose's heading error (rad, 0..pi) and horizontal position error (m) against the truth.
std::pair<double, double> pose_error(const SourceResult& result, const FloorPose& truth) {
  const double yaw = std::atan2(result.world_from_base.rotation(1, 0), result.world_from_base.rotation(0, 0));
  return {std::abs(std::remainder(yaw - truth.yaw, 2 * std::numbers::pi)),
          std::hypot(result.world_from_base.translation.x() - truth.x, result.world_from_base.translation.y() - truth.y)};
}

// Renders the scene as frame i of a drive at fps and gives the source that frame (no LED-off
// frame: outside-in mode).
void process_rendered(PoseSource& source, SceneRenderer& renderer, const SceneState& scene, int i, double fps,
                      SourceResult& result) {
  FrameTruth truth;
  const auto& pixels = renderer.render(scene, truth);
  source.process({Frame{static_cast<std::uint64_t>(i), static_cast<std::int64_t>(i * 1e9 / fps), false,
                        ImageView8(pixels.data(), 640, 480)},
                  nullptr},
                 result);
}

TEST(BoxSilhouette, MomentsMatchTheRenderedMask) {
  CleanBoxView view;
  const BoxSilhouette& box = view.box;
  for (const FloorPose pose : {FloorPose{2.0, 0.3, 0.4}, FloorPose{4.5, -0.6, 2.0}, FloorPose{6.3, 0.5, -1.2}}) {
    Silhouette seen;
    ASSERT_NO_FATAL_FAILURE(view.seen(pose, seen));
    Silhouette model_silhouette;
    ASSERT_TRUE(box.project(pose, model_silhouette));
    EXPECT_NEAR(model_silhouette.area / seen.area, 1, 0.04);
    EXPECT_NEAR(model_silhouette.cx, seen.cx, 0.3);
    EXPECT_NEAR(model_silhouette.cy, seen.cy, 0.3);
    const BoxFit fit = fit_box(box, seen);
    ASSERT_TRUE(fit.ok);
    EXPECT_NEAR(fit.pose.x, pose.x, 0.02);
    EXPECT_NEAR(fit.pose.y, pose.y, 0.02);
    // Far away and seen nearly end-on, one silhouette leaves the heading loose: the track
    // carries it there (the goal scenario).
    if (pose.x < 5) {
      EXPECT_NEAR(std::remainder(fit.pose.yaw - pose.yaw, std::numbers::pi), 0, 0.03) << pose.x;
    }
  }
}

// The renderer casts each pixel's ray through the lens the source models: through barrel
// distortion and a fisheye, the box's modelled silhouette (its corners projected through the
// lens) lands where the rendered one is, off the axis too.
TEST(BoxSilhouette, MomentsMatchTheRenderedMaskThroughALens) {
  WallCamera barrel, fisheye;
  barrel.intrinsics.distortion = {-0.3, 0.09, 0, 0, 0};
  fisheye.intrinsics = CameraIntrinsics{640, 480, 300, 300, 319.5, 239.5, LensModel::equidistant, {0.02, 0, 0, 0, 0}};
  for (const WallCamera& camera : {barrel, fisheye}) {
    CleanBoxView view(camera);
    for (const FloorPose pose : {FloorPose{2.2, 0.3, 0.4}, FloorPose{4.5, -0.6, 2.0}, FloorPose{3.0, 1.2, 0.9}}) {
      Silhouette seen;
      ASSERT_NO_FATAL_FAILURE(view.seen(pose, seen));
      Silhouette model_silhouette;
      ASSERT_TRUE(view.box.project(pose, model_silhouette));
      EXPECT_NEAR(model_silhouette.area / seen.area, 1, 0.04) << pose.x << ", " << pose.y;
      EXPECT_NEAR(model_silhouette.cx, seen.cx, 0.3) << pose.x << ", " << pose.y;
      EXPECT_NEAR(model_silhouette.cy, seen.cy, 0.3) << pose.x << ", " << pose.y;
      std::printf("lens %d, box at (%.1f, %.1f): centroid %.2f, %.2f px off, area ratio %.3f\n",
                  static_cast<int>(camera.intrinsics.model), pose.x, pose.y, model_silhouette.cx - seen.cx,
                  model_silhouette.cy - seen.cy, model_silhouette.area / seen.area);
    }
  }
}

TEST(AdaptiveBackground, ALightStepGivesNoBurstOfForeground) {
  WallCamera camera;
  SceneRenderer renderer(camera);
  renderer.auto_exposure = false;
  AdaptiveBackground background(AdaptiveBackgroundConfig{640, 480});
  std::vector<std::uint8_t> foreground(640 * 480);
  const MutableImageView8 mask(foreground.data(), 640, 480);
  SceneState scene;
  FrameTruth truth;
  for (int i = 0; i < 3; ++i) background.apply(ImageView8(renderer.render(scene, truth).data(), 640, 480), mask, {});
  for (const double lamp : {0.65, 1.0, 1.3}) {
    scene.lamp = lamp;
    const BackgroundStep step = background.apply(ImageView8(renderer.render(scene, truth).data(), 640, 480), mask, {});
    EXPECT_TRUE(step.light_change);
    EXPECT_LT(step.foreground_pixels, 640u * 480u / 1000u) << "lamp " << lamp;
  }
}

// Rectangles beyond the capacity are dropped and the background reports how many; the ones kept
// still protect their pixels from absorption.
TEST(AdaptiveBackground, ReportsProtectedRectanglesBeyondItsCapacity) {
  ProtectedRects protect;
  for (int k = 0; k < ProtectedRects::kCapacity + 3; ++k) protect.add({10 * k, 0, 10 * k + 5, 5});
  EXPECT_EQ(protect.count, ProtectedRects::kCapacity);
  EXPECT_EQ(protect.dropped, 3u);
  EXPECT_TRUE(protect.contains(0, 0));
  EXPECT_FALSE(protect.contains(10 * ProtectedRects::kCapacity, 0));
  AdaptiveBackground background(AdaptiveBackgroundConfig{64, 48});
  std::vector<std::uint8_t> frame(64 * 48, 40), foreground(64 * 48);
  const MutableImageView8 mask(foreground.data(), 64, 48);
  EXPECT_EQ(background.apply(ImageView8(frame.data(), 64, 48), mask, protect).protected_dropped, 3u);
  EXPECT_EQ(background.apply(ImageView8(frame.data(), 64, 48), mask, {}).protected_dropped, 0u);
}

TEST(OutsideInSource, GoalScenarioPosesTheRobotAndNeverThePerson) {
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera);
  // The robot is in view when the background starts: what was behind it shows as foreground until
  // it has driven off and that ghost is absorbed (about 3 s); scored from frame 35 on.
  const ScenarioScore score = run_scenario(rig, renderer, 140, 35, goal_scene, kFps);
  expect_scenario_goal(score, "outside-in goal scenario", 0.95);
}

// A webcam's rolling shutter (60 us a row: its 480 rows in 29 ms), the robot on the ellipse at
// 1 m/s, each row rendered from the robot at its own time. The same frames through a source told
// the line time and one not told it, and the drive rendered with a global shutter: the pose at the
// frame's time is within 2x of the global shutter's error, and without the correction it is not.
// A new track's heading needs its second fit, by which the motion is known (the arc from the
// first): no pose of this drive is the plain fit (pose_delay_ns). The robot enters in frame 1
// (the background starts from the empty floor: no start-up ghost).
TEST(OutsideInSource, RollingShutterGivesThePoseAtTheFrameTime) {
  constexpr std::int64_t kLineTimeNs = 60'000;
  constexpr int kFrames = 26, kScoredFrom = 5;
  const auto robot_at = [](double t) { return ellipse_pose(2 * t, 2.4); };  // from 2.5 m to the near end
  OutsideInRig corrected, uncorrected, global;
  SceneRenderer rolling_renderer(corrected.camera), global_renderer(global.camera);
  double sum2[3] = {0, 0, 0};
  int scored[3] = {0, 0, 0}, unknown_motion_poses = 0;
  const auto score = [&](int which, int i, const SourceResult& result) {
    if (!result.ok || i < kScoredFrom) return;
    const FloorPose truth = robot_at(i / kFps);
    const Eigen::Vector3d& p = result.world_from_base.translation;
    sum2[which] += std::pow(p.x() - truth.x, 2) + std::pow(p.y() - truth.y, 2);
    ++scored[which];
  };
  SourceResult result;
  for (int i = 0; i < kFrames; ++i) {
    const double t = i / kFps;
    const auto t_ns = static_cast<std::int64_t>(i * 1e9 / kFps);
    FrameTruth truth;
    const auto& rolling_pixels = rolling_renderer.render(
        [&](int v) {
          SceneState scene;
          if (i > 0) scene.robot = robot_at(t + static_cast<double>(v * kLineTimeNs) * 1e-9);
          return scene;
        },
        truth);
    const Frame rolling{static_cast<std::uint64_t>(i), t_ns, false, ImageView8(rolling_pixels.data(), 640, 480)};
    corrected.source->process({.on = rolling, .off = nullptr, .line_time_ns = kLineTimeNs}, result);
    unknown_motion_poses += result.ok && result.pose_delay_ns > 0;
    score(0, i, result);
    uncorrected.source->process({rolling, nullptr}, result);
    score(1, i, result);
    SceneState scene;
    if (i > 0) scene.robot = robot_at(t);
    const auto& global_pixels = global_renderer.render(scene, truth);
    global.source->process({Frame{static_cast<std::uint64_t>(i), t_ns, false, ImageView8(global_pixels.data(), 640, 480)},
                            nullptr},
                           result);
    score(2, i, result);
  }
  double rms[3];
  for (int k = 0; k < 3; ++k) rms[k] = std::sqrt(sum2[k] / std::max(scored[k], 1));
  std::printf("outside-in at 1 m/s, position RMS over %d/%d/%d poses: rolling shutter corrected %.1f mm, not corrected "
              "%.1f mm, global shutter %.1f mm; %d poses with the motion unknown\n",
              scored[0], scored[1], scored[2], 1e3 * rms[0], 1e3 * rms[1], 1e3 * rms[2], unknown_motion_poses);
  EXPECT_GE(scored[0], scored[2] - 2);
  EXPECT_GE(scored[2], kFrames - kScoredFrom - 1);
  EXPECT_LE(rms[0], 2 * rms[2]);
  EXPECT_GT(rms[1], 2 * rms[2]);
  EXPECT_EQ(unknown_motion_poses, 0);
}

TEST(OutsideInSource, NoPoseWhileTheRobotIsOutOfView) {
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera);
  // Drives sideways across the view at 4 m: in from one side, out at the other, and stays out.
  const auto scene_at = [](int i) {
    SceneState scene;
    scene.robot = FloorPose{4.0, -3.2 + 0.12 * i, std::numbers::pi / 2};
    return scene;
  };
  const ScenarioScore score = run_scenario(rig, renderer, 60, 0, scene_at, kFps);
  EXPECT_EQ(score.poses_without_robot, 0);
  EXPECT_GE(score.pose_rate(), 0.8);  // posed while whole in view (the first frames resolve its heading)
  EXPECT_EQ(score.flips, 0);
}

// The robot drives in, stops 5 m out and turns in place at 60 deg/s through a full turn, twice
// end-on to the camera, while a bright sun patch drifts past it (bench_outside_goal's stop-turn
// and lamp classes). Seen nearly end-on, the box and its mirror image fit within the mask's
// noise, both up to 20 degrees off on either side of the truth: a track that followed the fits
// lagged, then took the mirror branch (heading up to 180 degrees off, the position right; 29
// gross poses of 66). The heading filter carries the turn through the ambiguous fits and gives
// no pose while its heading is uncertain. Beside the robot, a background updated only away from
// any foreground froze and the drifting sun grew into a ghost merged with it.
TEST(OutsideInSource, TurnInPlaceEndOnToTheCameraBesideTheSunKeepsTheHeading) {
  constexpr int kEmpty = 5, kDriveIn = 8, kTurn = 60;
  constexpr double kDeg = std::numbers::pi / 180, kStartYaw = -100 * kDeg, kStep = 0.047;  // m per frame
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera, rig.config.body, 4);
  SourceResult result;
  int posed = 0, gross = 0;
  double worst_heading = 0, worst_position = 0;
  for (int i = 0; i < kEmpty + kDriveIn + kTurn; ++i) {
    SceneState scene;
    scene.sun = Eigen::Vector2d(5.8 - 0.01 * i, 0.5);
    if (i >= kEmpty) {
      const int to_go = std::max(kEmpty + kDriveIn - i, 0), turned = std::max(i - kEmpty - kDriveIn, 0);
      scene.robot = FloorPose{5.0 - kStep * to_go * std::cos(kStartYaw), 0.2 - kStep * to_go * std::sin(kStartYaw),
                              kStartYaw + turned * 6 * kDeg};
    }
    process_rendered(*rig.source, renderer, scene, i, kFps, result);
    if (!result.ok) continue;
    ASSERT_TRUE(scene.robot) << i;
    const auto [heading_error, position_error] = pose_error(result, *scene.robot);
    worst_heading = std::max(worst_heading, heading_error);
    worst_position = std::max(worst_position, position_error);
    gross += heading_error > 10 * kDeg || position_error > 0.10;
    ++posed;
  }
  std::printf("turn in place end-on beside the sun: %d of %d frames posed, worst heading %.1f deg, position %.0f mm, "
              "%d gross\n",
              posed, kDriveIn + kTurn, worst_heading / kDeg, 1000 * worst_position, gross);
  // Never the mirror branch, and no gross pose: the end-on fits, biased to one side of the truth
  // for several frames, were believed up to 12 degrees off while each fit's error counted as
  // independent noise; with the bias a state of the heading filter they no longer decide it.
  EXPECT_LT(worst_heading, 10 * kDeg);
  EXPECT_EQ(gross, 0);
  EXPECT_LT(worst_position, 0.10);
  // Posed where the heading is decided: the drive in and the broadside part of the turn (12 of
  // 68 frames; 20 and more before, with up to 4 gross).
  EXPECT_GE(posed, 12);
}

// The robot drives on while hidden for 1.2 s; as it comes back into view, a box-like blob lies
// 0.35 m behind where it was last seen (in bench_outside_goal's lamp class, the ghost of a
// drifting sun patch). The robot is where its last velocity takes it, 0.6 m on: a new track that
// took the blob nearest to where the robot was last seen followed the blob with the robot's
// heading, posed 1.6 m off (--seed=5, lamp class, scene 0, frames 196-199).
TEST(OutsideInSource, ReacquiresTheRobotWhereItsLastVelocityTakesItNotTheBlobWhereItWasSeen) {
  constexpr int kEmpty = 5, kDrive = 12, kHidden = 12, kAfter = 8;
  constexpr double kStep = 0.047;  // m per frame: 0.47 m/s
  // A robot that turns at most 30 deg/s cannot reach its mirror heading in the 1.2 s hidden, so
  // it keeps its heading's branch (a 90 deg/s one could: its branch is resolved anew).
  constexpr double kYawRate = 30 * std::numbers::pi / 180;
  const auto robot_at = [](int i) { return FloorPose{3.5, -1.5 + kStep * (i - kEmpty), std::numbers::pi / 2}; };
  const int last_seen = kEmpty + kDrive - 1, back = kEmpty + kDrive + kHidden;
  // The decoy: the same box, parked 0.35 m behind the last place the robot was seen, composited
  // into the frames from the robot's return on (it appears then, so no background holds it).
  FloorPose decoy = robot_at(last_seen);
  decoy.y -= 0.35;
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera, rig.config.body, 5);
  renderer.auto_exposure = false;
  SceneRenderer clean(rig.camera, rig.config.body);
  clean.auto_exposure = false;
  clean.noise_sigma = 0;
  FrameTruth truth;
  const std::vector<std::uint8_t> empty = clean.render(SceneState{}, truth);
  SceneState with_decoy;
  with_decoy.robot = decoy;
  const std::vector<std::uint8_t> decoy_view = clean.render(with_decoy, truth);
  SourceResult result;
  int posed_after = 0, gross = 0;
  for (int i = 0; i < back + kAfter; ++i) {
    SceneState scene;
    if (i >= kEmpty && (i <= last_seen || i >= back)) scene.robot = robot_at(i);
    std::vector<std::uint8_t> pixels = renderer.render(scene, truth);
    if (i >= back)
      for (std::size_t p = 0; p < pixels.size(); ++p)
        if (std::abs(decoy_view[p] - empty[p]) > 10) pixels[p] = decoy_view[p];
    const Frame frame{static_cast<std::uint64_t>(i), static_cast<std::int64_t>(i * 1e9 / kFps), false,
                      ImageView8(pixels.data(), 640, 480)};
    SourceInput input{frame, nullptr};
    input.limits.yaw_rate = kYawRate;
    rig.source->process(input, result);
    if (!result.ok) continue;
    ASSERT_TRUE(scene.robot) << i;
    const auto [heading_error, position_error] = pose_error(result, *scene.robot);
    gross += heading_error > 10 * std::numbers::pi / 180 || position_error > 0.10;
    posed_after += i >= back;
  }
  EXPECT_EQ(gross, 0);
  EXPECT_GE(posed_after, kAfter - 1);  // taken back with its heading at once
}

// A nearly square box (0.40 x 0.34 x 0.22 m) drives 1.2 m toward the camera and stands 1.4 m
// from its foot, nearly broadside, for 3 s: bench_outside_goal --seed=5, stop-turn class, scene 1
// (its camera, its floor reference, one 0.5 m tile clicked to 0.3 px, its sun; frames 0-70).
// From about 1.6 m on, the fits' heading is 10-12 degrees off, the same way in every frame (the
// mask's edges; heading_per_px 6-7 degrees), and stays so while the robot stands. The filter,
// which took each fit's error as independent noise, averaged 30 of them into a heading it
// believed to 4-5 degrees, and posed it 10-12 degrees off. With the fits' bias as a state that
// keeps its value while the view does, and the direction of travel as a heading free of it, the
// robot is posed while it drives and no pose is gross.
TEST(OutsideInSource, ARobotStandingStillIsNotPosedOnItsFitsBias) {
  constexpr double kDeg = std::numbers::pi / 180;
  // The benchmark scene's frames: the robot appears at frame 10 and arrives at frame 56 after 46
  // steps; the old filter's gross poses were at frames 68-77.
  constexpr int kAppears = 10, kArrives = 56, kLast = 70;
  constexpr double kYaw = 2.496382085;  // rad, 143 degrees
  const Eigen::Vector2d start(2.893120531, -0.514612541), stop(1.173025083, 0.780059375);
  WallCamera camera;
  camera.intrinsics = CameraIntrinsics{640, 480, 478.227434, 478.227434, 319.5, 239.5, LensModel::plumb_bob, {}};
  camera.height = 2.768523368;
  camera.pitch_deg = 50.284591319;
  OutsideInConfig config;
  config.body = BoxBody{0.403535432, 0.337652243, 0.215426193};
  config.floor_reference.world = {{1.5, -0.5}, {2.0, -0.5}, {2.0, 0.0}, {1.5, 0.0}};
  config.floor_reference.pixels = {{396.864279, 334.672710}, {389.642983, 272.166255}, {319.475972, 271.793606},
                                   {319.135291, 334.909042}};
  config.floor_reference.pixel_sigma = 0.3;
  OutsideInSource source(SourceSetup{camera.intrinsics, RigidTransform{}, Dof::planar3, MarkerMap{}}, config);
  SceneRenderer renderer(camera, config.body, 2);
  SourceResult result;
  int posed_driving = 0, posed_standing = 0, gross = 0;
  for (int i = 0; i <= kLast; ++i) {
    SceneState scene;
    scene.sun_strength = 0.2;
    scene.sun = Eigen::Vector2d(1.673719065 + 0.00060256 * i, -1.500679554 + 0.00998183 * i);
    if (i >= kAppears) {
      const double to_go = std::max(kArrives - i, 0) / double(kArrives - kAppears);
      scene.robot = FloorPose{stop.x() + (start.x() - stop.x()) * to_go, stop.y() + (start.y() - stop.y()) * to_go, kYaw};
    }
    process_rendered(source, renderer, scene, i, kFps, result);
    if (!result.ok) continue;
    ASSERT_TRUE(scene.robot) << i;
    const auto [heading_error, position_error] = pose_error(result, *scene.robot);
    if (heading_error > 10 * kDeg || position_error > 0.10) {
      ++gross;
      ADD_FAILURE() << "frame " << i << ": " << heading_error / kDeg << " deg, " << position_error << " m off";
    }
    ++(i < kArrives ? posed_driving : posed_standing);
  }
  std::printf("nearly square box driving in and standing: %d poses driving, %d standing, %d gross\n", posed_driving,
              posed_standing, gross);
  EXPECT_EQ(gross, 0);
  EXPECT_GE(posed_driving, 20);  // of 46: the direction of travel decides the heading while it drives (13 before)
}

// A room of bench_outside_goal (its seed, class and scene; `varied`: with the second generator's
// lens, frame rate, exits and reference, else --plain), frames 0 to `last` through the source as
// the benchmark gives them, with the dark robot (RobotLook{}, every room's look before the family
// drew looks; the room's geometry, drive and light are the same) or (own_look) the room's drawn
// look: each frame's pose error (when posed) and outcome.
struct ReplayedFrame {
  bool posed = false;
  double heading_error = 0, position_error = 0;  // rad, m
  double heading_sigma = 0;                      // rad: the pose's own
  std::string outcome;
};
std::vector<ReplayedFrame> replay_goal_room(int seed, outside_goal::RoomClass room_class, int scene, int last,
                                            bool varied = false, bool own_look = false) {
  std::mt19937 rooms = outside_goal::room_generator(seed, room_class);
  std::mt19937 variations = outside_goal::variation_generator(seed, room_class);
  outside_goal::Room room;
  for (int k = 0; k <= scene; ++k) room = outside_goal::draw_room(room_class, rooms, varied ? &variations : nullptr);
  OutsideInConfig config;
  config.floor_reference = room.reference;
  config.body = room.body;
  OutsideInSource source(SourceSetup{room.camera.intrinsics, RigidTransform{}, Dof::planar3, MarkerMap{}}, config);
  SceneRenderer renderer(room.camera, room.body, static_cast<unsigned>(scene + 1));
  if (own_look) renderer.look = room.look;
  SourceResult result;
  std::vector<ReplayedFrame> frames;
  for (int i = 0; i <= last; ++i) {
    const SceneState& state = room.frames[static_cast<std::size_t>(i)];
    process_rendered(source, renderer, state, i, room.fps, result);
    ReplayedFrame& frame = frames.emplace_back();
    frame.outcome = result.outcome;
    if (!result.ok) continue;
    EXPECT_TRUE(state.robot) << "frame " << i << " posed without a robot";
    if (!state.robot) continue;
    frame.posed = true;
    std::tie(frame.heading_error, frame.position_error) = pose_error(result, *state.robot);
    frame.heading_sigma = std::sqrt(result.covariance(5, 5));
  }
  return frames;
}

// The replayed poses against the goal's gross error (10 degrees or 0.10 m off: each such frame
// fails the test): how many were posed from frame `count_from` on, and the worst heading error,
// in degrees and in the pose's own sigmas.
struct ReplaySummary {
  int posed = 0;
  double worst_heading = 0;         // rad
  double worst_heading_sigmas = 0;  // heading error / the pose's heading sigma
  std::size_t worst_sigmas_frame = 0;
};
ReplaySummary expect_no_gross_pose(const std::vector<ReplayedFrame>& frames, std::size_t count_from = 0) {
  constexpr double kDeg = std::numbers::pi / 180;
  ReplaySummary summary;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const ReplayedFrame& frame = frames[i];
    if (!frame.posed) continue;
    EXPECT_LT(frame.heading_error, 10 * kDeg) << "frame " << i;
    EXPECT_LT(frame.position_error, 0.10) << "frame " << i;
    summary.posed += i >= count_from;
    summary.worst_heading = std::max(summary.worst_heading, frame.heading_error);
    if (frame.heading_error / frame.heading_sigma > summary.worst_heading_sigmas) {
      summary.worst_heading_sigmas = frame.heading_error / frame.heading_sigma;
      summary.worst_sigmas_frame = i;
    }
  }
  return summary;
}

// bench_outside_goal --seed=23, stop-turn class, scene 1: the robot stands still, then turns in
// place through a view where the floor reference's error (one tile clicked to 0.3 px, a typical
// draw) moves the fits' heading 8 degrees; they lag the turn by up to 12 degrees (frames 90-98;
// with the exact tile corners, 3). Counted in the fits' bias, that error keeps the filter from
// believing them: no pose is 10 degrees off (frame 94 was 11.3 degrees off at 5.0 claimed).
TEST(OutsideInSource, AFitsErrorFromTheFloorReferenceIsNotBelievedThroughATurnInPlace) {
  constexpr double kDeg = std::numbers::pi / 180;
  const ReplaySummary poses =
      expect_no_gross_pose(replay_goal_room(23, outside_goal::RoomClass::stop_turn_reverse, 1, 110));
  std::printf("turn in place through the floor reference's worst view: %d poses, worst heading %.1f deg\n", poses.posed,
              poses.worst_heading / kDeg);
  EXPECT_GE(poses.posed, 60);
}

// bench_outside_goal --seed=23, lamp class, scene 2: the robot drives straight (at -105 degrees,
// 4.3 m out) while a bright sun patch's ghost merges with it for 1.8 s (frames 144-161). The
// merged blob is fitted 10-12 cm and 30-180 degrees off, at 1.3-6.4 px residual RMS (the robot
// alone: 0.03-0.4). Taken as the robot's fits, their positions bent the travel line and the
// heading was posed 12-13 degrees off just after the merge (frames 163-164); their headings alone
// drew the filter onto the mirror branch (180 degrees off). A fit the box does not explain
// measures nothing: no pose, the track follows it, and after 1.8 s unmeasured (the robot could
// have turned round) the heading is resolved anew from its travel. On aarch64 (qemu) the scene
// renders a hair differently and none of frames 144-158 is `not_explained` there (the ghost's
// growth is that sensitive); the claims below hold there too.
TEST(OutsideInSource, ARobotMergedWithTheSunsGhostIsNotPosedFromTheMergedFits) {
  constexpr int kMergeTo = 158, kLast = 175;
  const ReplaySummary poses = expect_no_gross_pose(replay_goal_room(23, outside_goal::RoomClass::light, 2, kLast), kMergeTo + 1);
  EXPECT_GE(poses.posed, 8);  // of the 17 after the merge (12 on x86-64)
}

// With the two motion models (heading_filter.hpp) a driving robot's heading is believed to its
// travel lines, so what bends or repeats a line shows. bench_outside_goal --seed=11, lamp class,
// scene 2: the robot drives beside the sun's ghost (frames 157-168), its fits between the merged
// ones explained to 0.7-0.95 px yet pulled sideways smoothly; the line through them turned 13
// degrees and frame 165 was posed 13.8 degrees off. --seed=23, lamp class, scene 3: the robot
// stops at frame 143 and turns in place at 59 deg/s; its last line, measured again each frame
// through the same points, held the turn back and frame 148 was posed 11.6 degrees off.
TEST(OutsideInSource, NoPoseFromATravelLineBesideAMergeOrAfterTheRobotStopped) {
  const ReplaySummary beside_ghost = expect_no_gross_pose(replay_goal_room(11, outside_goal::RoomClass::light, 2, 175));
  const ReplaySummary turn_after_stop = expect_no_gross_pose(replay_goal_room(23, outside_goal::RoomClass::light, 3, 160));
  std::printf("beside the ghost: %d poses; turning after a stop: %d poses\n", beside_ghost.posed, turn_after_stop.posed);
  EXPECT_GE(beside_ghost.posed, 95);  // 118 on x86-64
  EXPECT_GE(turn_after_stop.posed, 60);  // 73 on x86-64
}

// bench_outside_goal --seed=47, person class, scene 0: the robot drives to 0.9 m from the
// camera's foot (2 m up) and turns in place at 60 deg/s. That close, one of its faces is within
// the floor's brightness range and drops out of the foreground: the blob is 5-20 % smaller than
// the box, fitted at 1-4 px residual RMS, its heading lagging the turn by 6-8 degrees. The filter,
// which took those fits to the mask's 1 px error, posed frame 37 10.5 degrees off.
TEST(OutsideInSource, ABlobMissingAFaceIsNotPosedThroughATurnInPlace) {
  EXPECT_GE(expect_no_gross_pose(replay_goal_room(47, outside_goal::RoomClass::person, 0, 70)).posed, 25);  // the drive in (frames 12-30) and out (58-70)
}

// bench_outside_goal --seed=5, drive class, scene 1: the dark robot drives straight (at -114
// degrees, 4 m out) to a stop at frame 85. Over frames 83-85 its lowest corner crosses a tile
// joint, where the robot is 0.5-0.6 times as bright as the joint (the background's shadow range):
// that row drops out of the foreground and the opening removes the 3-4 rows of the tip beyond it.
// The box fit explains the shortened blob to 0.2-0.4 px as the whole box turned by 5-10 degrees
// and moved 25-40 mm sideways, and the travel line turned with the positions: frames 84-85 were
// posed 8.5 and 10.0 degrees off at 3.9 and 4.1 degrees claimed. The foreground dropped 3 rows
// beyond the blob's extent (more than the fit allows for, 2) marks the blob as short of the robot:
// its heading is measured with the shortfall in its variance, its position is no point of the
// travel line (frames 84-85 are heading_uncertain now).
TEST(OutsideInSource, ARobotWhoseTipATileJointCutsOffIsNotPosedFromTheCutBlob) {
  const ReplaySummary poses = expect_no_gross_pose(replay_goal_room(5, outside_goal::RoomClass::drive, 1, 100));
  std::printf("a tip cut off by a tile joint: %d poses, worst heading %.2f sigma\n", poses.posed, poses.worst_heading_sigmas);
  // Every heading within 2 sigma of its own (the uncut fits: within 1.1; the cut ones were 2.2-2.5).
  EXPECT_LT(poses.worst_heading_sigmas, 2) << "frame " << poses.worst_sigmas_frame;
  EXPECT_GE(poses.posed, 15);  // of 22: the drive in from frame 68 on, and after the turn in place
}

// bench_outside_goal --seed=71, stop-turn class, scene 0: the robot stands and turns in place with
// its tip cut off by a tile joint, 3 px of dropped extent, for 1.7 s (frames 110-133). Had such a
// fit measured nothing, the heading went unmeasured that long, a turn of the symmetry's half
// could have passed unseen, the branch was resolved again by travel as forward while the robot
// reversed, and frames 155-219 were posed 180 degrees off. Its heading still tells the branch,
// with the shortfall in its variance; only its position stays out of the travel line.
TEST(OutsideInSource, ATipCutOffForSecondsKeepsTheHeadingsBranch) {
  EXPECT_GE(expect_no_gross_pose(replay_goal_room(71, outside_goal::RoomClass::stop_turn_reverse, 0, 165)).posed, 60);
}

// bench_outside_goal --seed=5, person class, scene 1 (a fisheye, 15 fps): the robot turns in place
// at 60 deg/s; a person hides it from frame 95 on for 1.5 s, while it turns on by about 90
// degrees. The new track at frame 118, where the robot was last seen, took that heading's branch
// and frames 126-288 were posed 180 degrees off. A robot that may have turned onto the mirror
// branch unseen (90 deg/s for 1.5 s) is taken back with its branch unknown, resolved by travel.
TEST(OutsideInSource, ARobotThatMayHaveTurnedRoundWhileHiddenIsNotTakenBackOnItsOldBranch) {
  const std::vector<ReplayedFrame> frames = replay_goal_room(5, outside_goal::RoomClass::person, 1, 140, true);
  const ReplaySummary summary = expect_no_gross_pose(frames, 118);
  std::printf("taken back after the person: %d poses of frames 118-140, worst heading %.1f deg\n", summary.posed,
              summary.worst_heading * 180 / std::numbers::pi);
  EXPECT_GE(summary.posed, 5);
}

// Seed 47's person room 3: a fisheye at 30 fps, the robot turning in place at 60 deg/s (frames
// 405-477), then driving on. The fits' frame-to-frame noise, counted as travel, renewed their bias
// every frame at 30 fps: the filter took the fits' rotation as bias, stood still through the turn,
// and posed the drive after it 177 degrees off (frames 531-534 and on).
TEST(OutsideInSource, AThirtyFpsTurnInPlaceIsFollowedNotTakenAsTheFitsBias) {
  const std::vector<ReplayedFrame> frames = replay_goal_room(47, outside_goal::RoomClass::person, 3, 560, true);
  const ReplaySummary summary = expect_no_gross_pose(frames, 400);
  std::printf("30 fps turn in place and the drive after it: %d poses of frames 400-560, worst heading %.1f deg\n",
              summary.posed, summary.worst_heading * 180 / std::numbers::pi);
}

// bench_outside_goal --seed=11, drive class, scene 0 (30 fps): the robot comes back into view close
// to the camera and turns in place before it has a track. The background absorbed still
// foreground after 10 frames, 0.33 s at 30 fps, and took the robot in: no pose over frames
// 473-629. Counted as 1 s of the measured frame period, as at 10 fps, it keeps the robot.
TEST(OutsideInSource, AThirtyFpsRobotIsNotAbsorbedSoonerThanATenFpsOne) {
  const std::vector<ReplayedFrame> frames = replay_goal_room(11, outside_goal::RoomClass::drive, 0, 629, true);
  const ReplaySummary summary = expect_no_gross_pose(frames, 473);
  std::printf("30 fps robot back in view: %d poses of frames 473-629\n", summary.posed);
  EXPECT_GE(summary.posed, 40);
}

// bench_outside_goal --seed=11, person class, scene 1 (30 fps, barrel k1 -0.25): a mid grey robot
// (between the tiles' shades) that the foreground never sees whole; the appearance fit finds it
// mid-drive (frame 229). A new track that took its first travel as forward put it half a turn off
// from frame 236 on (348 poses 179.5 degrees off, session 31's trial); its branch now waits for a
// metre of travel mostly one way (travel_branch.hpp).
TEST(OutsideInSource, AMidGreyRobotFoundMidDriveIsNotPosedOnTheMirrorBranch) {
  const std::vector<ReplayedFrame> frames =
      replay_goal_room(11, outside_goal::RoomClass::person, 1, 420, true, true);
  const ReplaySummary summary = expect_no_gross_pose(frames);
  std::printf("mid grey robot found mid-drive: %d poses of frames 0-420, worst heading %.1f deg\n", summary.posed,
              summary.worst_heading * 180 / std::numbers::pi);
  EXPECT_GE(summary.posed, 100);
}

TEST(OutsideInSource, AllocatesNothingPerFrame) {
  OutsideInRig rig;
  SceneRenderer renderer(rig.camera);
  SourceResult result;
  std::uint64_t allocations = 0;
  int poses = 0;
  for (int i = 0; i < 40; ++i) {
    FrameTruth truth;
    const auto& pixels = renderer.render(goal_scene(i), truth);
    const Frame frame{static_cast<std::uint64_t>(i), static_cast<std::int64_t>(i * 1e8), false,
                      ImageView8(pixels.data(), 640, 480)};
    AllocationCounter counter;
    rig.source->process({frame, nullptr}, result);
    allocations += counter.count();
    poses += result.ok;
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(poses, 0);  // the counted frames include found poses
}

}  // namespace
}  // namespace irloc::test
