// SurveyWriter on a disk that fills and frees again: a failed map write leaves the previous map,
// says so once however often it is tried again, and the next write that works replaces the map
// and says so. And on rendered strobe pairs: the localizer is given the established markers with
// their current sigmas, close to the written map's, and an attempt that writes no map allocates
// nothing.

#include <signal.h>
#include <sys/resource.h>

#include <cmath>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "algo/geometry/rigid_transform.hpp"
#include "firmware/survey_writer.hpp"
#include "io/config/config_file.hpp"
#include "io/config/map_file.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/dot/dot_scene.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/memory_log.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::firmware {
namespace {

using ::testing::HasSubstr;

TEST(SurveyWriter, AFailedMapWriteKeepsThePreviousMapAndIsTriedAgain) {
  test::TempDir dir;
  sim::write_synthetic_dataset(dir / "dataset", sim::SyntheticDatasetOptions{});
  std::ofstream(dir / "dataset" / "map.yaml", std::ios::app) << "    fixed: true\n";
  io::RobotConfig config = io::load_robot_config(dir / "dataset" / "config.yaml");
  config.setup.dot.observe_every_marker = true;
  Localizer localizer(std::move(config.setup));
  const std::filesystem::path output = dir / "surveyed.yaml";
  const std::string previous = "# the map of an earlier run\n" + test::read_text(dir / "dataset" / "map.yaml");
  std::ofstream(output) << previous;
  test::MemoryLog log;
  SurveyWriter writer(output, config.map_file, localizer, log.file(), std::chrono::nanoseconds(1));
  StrobePair pair;
  const auto attempt_at = [&](std::int64_t t_ns) {
    pair.on.t_ns = t_ns;
    writer.on_attempt(pair, std::nullopt, true, PoseEstimate{});
  };

  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto previous_handler = ::signal(SIGXFSZ, SIG_IGN);
  rlimit full = saved;
  full.rlim_cur = 64;  // less than any map
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &full), 0);
  for (std::int64_t t_ns = 1; t_ns <= 4; ++t_ns) attempt_at(t_ns);  // writes at 2, 3 and 4
  writer.wait_until_written();
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, previous_handler);
  EXPECT_TRUE(writer.last_write_failed());
  EXPECT_EQ(test::read_text(output), previous);
  EXPECT_EQ(log.text(), "irlocd: --survey " + output.string() +
                            ": cannot write the map (write): File too large: the previous map stays; trying again at "
                            "the next write\n");

  attempt_at(5);
  writer.wait_until_written();
  EXPECT_FALSE(writer.last_write_failed());
  EXPECT_THAT(log.text(), ::testing::EndsWith("irlocd: --survey " + output.string() + ": written again\n"));
  EXPECT_NE(test::read_text(output), previous);
  const MarkerMap map = io::load_marker_map(output);
  ASSERT_EQ(map.dot_markers.size(), 1u);
  EXPECT_TRUE(map.dot_markers[0].fixed);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::AnyOf("dataset", "surveyed.yaml")) << "left behind";
  }
}

TEST(SurveyWriter, LocalizationUsesTheEstablishedMarkersWithTheirSigmasAndAnAttemptWithoutAWriteAllocatesNothing) {
  test::TempDir dir;
  test::Scene scene;
  DotMarker reference = test::ceiling_marker(1782, 0.0, 0.0, 0.3);
  reference.fixed = true;
  const DotMarker other = test::ceiling_marker(613, 0.5, 0.2, -1.1);
  scene.add_marker(reference);
  scene.add_marker(other);
  LocalizerSetup setup;
  setup.camera = scene.camera;
  setup.mount = to_rigid(scene.mount);
  setup.map.dot_markers = {reference, other};
  setup.dot.observe_every_marker = true;
  Localizer localizer(setup);
  const std::filesystem::path output = dir / "surveyed.yaml";
  test::MemoryLog log;
  // A pair every 0.1 s, a map every 0.5 s.
  SurveyWriter writer(output, dir / "map.yaml", localizer, log.file(), std::chrono::milliseconds(500));

  int sigmas_used = 0;
  for (int k = 0; k < 35; ++k) {
    scene.world_from_base = test::level_pose(0.25 + 0.1 * std::sin(0.3 * k), 0.1 + 0.1 * std::cos(0.2 * k), 0.05 * k);
    scene.seed = static_cast<unsigned>(k + 1);
    Image8 on, off;
    scene.render(on, off);
    StrobePair pair = test::strobe_pair(on, off, static_cast<std::uint64_t>(2 * k + 1));
    pair.on.t_ns = 100'000'000LL * k;
    const PoseEstimate estimate = localizer.process(pair);
    ASSERT_TRUE(estimate.ok) << "attempt " << k;
    const MarkerMap written_before = std::filesystem::exists(output) ? io::load_marker_map(output) : MarkerMap{};
    if (k % 5 == 0) {  // writes the map (from 0.5 s on)
      writer.on_attempt(pair, localizer.last_strobe_verdict(), true, estimate);
      writer.wait_until_written();  // the file's thread allocates while it writes
    } else {
      test::AllocationCounter counter;
      writer.on_attempt(pair, localizer.last_strobe_verdict(), true, estimate);
      EXPECT_EQ(counter.count(), 0u) << "attempt " << k;
    }
    for (const DotMarker& used : localizer.setup().map.dot_markers) {
      // The fixed marker is exact; the other is used once established, always with its sigma.
      ASSERT_EQ(used.sigma.has_value(), !used.fixed) << "marker " << used.id << ", attempt " << k;
      if (used.fixed) continue;
      ++sigmas_used;
      EXPECT_LT(used.sigma->head<2>().maxCoeff(), 0.005) << "established: within the established sigma";
      const DotMarker* written = written_before.find_dot_marker(used.id);
      if (written != nullptr && written->sigma) {
        // The map written at most 0.5 s before: the sigma it wrote, give or take what the
        // sightings since have added.
        EXPECT_LT(used.sigma->head<2>().maxCoeff(), 1.5 * written->sigma->head<2>().maxCoeff() + 1e-4)
            << "attempt " << k;
      }
    }
  }
  // The other marker is established after a few sightings and localizes with its sigma from then on.
  EXPECT_GE(sigmas_used, 25);
  EXPECT_EQ(log.text(), "");
}

}  // namespace
}  // namespace irloc::firmware
