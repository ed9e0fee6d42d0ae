// Strobe scheduling and sync on the simulated camera + LEDs (hal/sim): the frame loop must label
// frames as they were really lit, notice within one pair (two frames) when they are not, never
// compute a pose from a pair whose LED-on frame was not lit or whose LED-off frame was, and
// resynchronise a wrong latency by itself.

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/frame_loop.hpp"
#include "firmware/loop_outputs.hpp"
#include "firmware/protocol/mavlink_pose_stream.hpp"
#include "hal/linux/termios_serial.hpp"
#include "hal/sim/strobed_scene_camera.hpp"
#include "tests/support/pseudo_terminal.hpp"
#include "tests/support/allocation_counter.hpp"

namespace irloc::firmware {
namespace {

struct Attempt {
  std::uint64_t on_seq;
  std::optional<std::uint64_t> off_seq;
  std::optional<StrobeVerdict> verdict;
  bool computed;
  bool on_truly_lit;   // ground truth from the simulator, taken when the attempt was made
  bool off_truly_lit;
};

class Recorder final : public AttemptObserver {
 public:
  explicit Recorder(const hal::StrobedSceneCamera& camera) : camera_(camera) {}
  void on_attempt(const StrobePair& pair, std::optional<StrobeVerdict> verdict, bool computed, const PoseEstimate&) override {
    attempts.push_back({pair.on.seq, pair.off ? std::optional(pair.off->seq) : std::nullopt, verdict, computed,
                        camera_.truly_lit(pair.on.seq), pair.off && camera_.truly_lit(pair.off->seq)});
  }
  std::vector<Attempt> attempts;

 private:
  const hal::StrobedSceneCamera& camera_;
};

LocalizerSetup setup_for(const hal::StrobedSceneSettings& scene) {
  LocalizerSetup setup;
  setup.camera.width = scene.width;
  setup.camera.height = scene.height;
  return setup;
}

struct LoopRun {
  std::vector<Attempt> attempts;
  FrameLoopStats stats;
  StrobeSyncStats sync;
};

LoopRun run(const hal::StrobedSceneSettings& scene, unsigned int board_latency, hal::StrobedSceneCamera*& camera_out,
        std::optional<hal::StrobedSceneCamera>& storage) {
  storage.emplace(scene);
  camera_out = &*storage;
  Localizer localizer(setup_for(scene));
  Recorder recorder(*camera_out);
  FrameLoopIo io;
  io.attempts.add(&recorder);
  recorder.attempts.reserve(scene.frames);
  const std::atomic<bool> leds_enabled{true};
  FrameLoop loop(*camera_out, localizer, io, LiveStrobing{*camera_out, StrobeSync(board_latency), leds_enabled});
  while (loop.step()) {
  }
  return {recorder.attempts, loop.stats(), loop.strobe_sync()->stats()};
}

// No pose from a pair the LEDs did not really light as labelled.
void expect_only_true_pairs_computed(const LoopRun& result, const hal::StrobedSceneCamera&) {
  for (const Attempt& attempt : result.attempts) {
    if (!attempt.computed || !attempt.off_seq) continue;
    EXPECT_TRUE(attempt.on_truly_lit) << "pose from unlit on-frame " << attempt.on_seq;
    EXPECT_FALSE(attempt.off_truly_lit) << "pose against lit off-frame " << *attempt.off_seq;
  }
}

TEST(StrobeSync, RightLatencyVerifiesEveryPairAfterTheFirstCommandTakesEffect) {
  hal::StrobedSceneSettings scene;
  scene.frames = 60;
  scene.pipeline_depth = 2;
  std::optional<hal::StrobedSceneCamera> storage;
  hal::StrobedSceneCamera* camera = nullptr;
  const LoopRun result = run(scene, 2, camera, storage);
  EXPECT_EQ(result.stats.pose_attempts, 30u);
  // Frames 0 and 1 are exposed before the first command: the first pair has no contrast.
  EXPECT_EQ(result.sync.verified, 29u);
  EXPECT_EQ(result.sync.swapped, 0u);
  EXPECT_EQ(result.sync.resyncs, 0u);
  expect_only_true_pairs_computed(result, *camera);
}

TEST(StrobeSync, WrongLatencyIsCaughtAtTheFirstPairAndResynchronised) {
  hal::StrobedSceneSettings scene;
  scene.frames = 60;
  scene.pipeline_depth = 2;
  std::optional<hal::StrobedSceneCamera> storage;
  hal::StrobedSceneCamera* camera = nullptr;
  const LoopRun result = run(scene, 1, camera, storage);  // the board says 1: wrong parity
  // Frames 0-2 are unlit (before the first command takes effect); pair (4, 3) is the first with
  // LED contrast, and it is caught.
  ASSERT_GE(result.attempts.size(), 3u);
  EXPECT_EQ(result.attempts[1].verdict, StrobeVerdict::no_contrast);
  EXPECT_EQ(result.attempts[2].on_seq, 4u);
  EXPECT_EQ(result.attempts[2].verdict, StrobeVerdict::swapped);
  EXPECT_FALSE(result.attempts[2].computed);
  EXPECT_EQ(result.sync.resyncs, 1u);
  EXPECT_GE(result.sync.swapped, 2u);
  EXPECT_LE(result.sync.swapped, 3u);
  expect_only_true_pairs_computed(result, *camera);
  // After the resync every pair verifies: the last 20 attempts were all computed.
  for (std::size_t i = result.attempts.size() - 20; i < result.attempts.size(); ++i) {
    EXPECT_EQ(result.attempts[i].verdict, StrobeVerdict::verified) << "attempt " << i;
  }
}

TEST(StrobeSync, LossOfSyncMidRunIsCaughtWithinTwoFrames) {
  hal::StrobedSceneSettings scene;
  scene.frames = 100;
  scene.pipeline_depth = 1;
  scene.depth_change_at_seq = 40;
  scene.pipeline_depth_after_change = 2;
  std::optional<hal::StrobedSceneCamera> storage;
  hal::StrobedSceneCamera* camera = nullptr;
  const LoopRun result = run(scene, 1, camera, storage);
  expect_only_true_pairs_computed(result, *camera);
  // Frame 40 is the first exposed out of step; the pair of frame 42 is the first with the
  // contrast to show it, and it is refused.
  for (const Attempt& attempt : result.attempts) {
    if (attempt.on_seq < 40) {
      EXPECT_EQ(attempt.verdict == StrobeVerdict::verified, attempt.on_seq > 0) << attempt.on_seq;
    } else if (attempt.on_seq == 40) {
      EXPECT_EQ(attempt.verdict, StrobeVerdict::no_contrast);
    } else if (attempt.on_seq == 42) {
      EXPECT_EQ(attempt.verdict, StrobeVerdict::swapped);
    } else if (attempt.on_seq >= 50) {
      EXPECT_EQ(attempt.verdict, StrobeVerdict::verified) << attempt.on_seq;
    }
  }
  EXPECT_EQ(result.sync.resyncs, 1u);
}

TEST(StrobeSync, DroppedFramesNeverGiveAPoseFromAMislitFrame) {
  hal::StrobedSceneSettings scene;
  scene.frames = 120;
  scene.pipeline_depth = 1;
  scene.dropped_seqs = {11, 30, 31, 57, 58, 59, 90};
  std::optional<hal::StrobedSceneCamera> storage;
  hal::StrobedSceneCamera* camera = nullptr;
  const LoopRun result = run(scene, 1, camera, storage);
  EXPECT_EQ(result.stats.dropped_frames, 7u);
  EXPECT_EQ(result.sync.resyncs, 0u);  // a drop is not a lost sync
  expect_only_true_pairs_computed(result, *camera);
  EXPECT_GE(result.sync.verified, 45u);
}

TEST(StrobeSync, TheLiveLoopAllocatesNothingPerFrame) {
  hal::StrobedSceneSettings scene;
  scene.frames = 200;
  hal::StrobedSceneCamera camera(scene);
  Localizer localizer(setup_for(scene));
  test::PseudoTerminal pty;  // nobody reads it: the serial port drops and counts
  hal::TermiosSerial serial(pty.slave_path(), 115200);
  MavlinkPoseStream encoder({});
  SerialLink link(serial, encoder, stderr);
  PoseStreamOutput stream(link, camera);
  FrameLoopIo io;
  io.poses.add(&stream);
  const std::atomic<bool> leds_enabled{true};
  FrameLoop loop(camera, localizer, io, LiveStrobing{camera, StrobeSync(1), leds_enabled});
  for (int i = 0; i < 10; ++i) loop.step();
  test::AllocationCounter counter;
  while (loop.step()) {
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(loop.stats().frames, 200u);
  // Heartbeats from the link's own clock, on its own thread: on a loaded machine the 200 frames
  // can be done before that thread first runs, so it is given up to 5 s.
  for (int waited_ms = 0; serial.messages_sent() == 0 && waited_ms < 5000; waited_ms += 10) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GT(serial.messages_sent(), 0u);
}

}  // namespace
}  // namespace irloc::firmware
