// SurveyWriter on a disk that fills and frees again: a failed map write leaves the previous map,
// says so once however often it is tried again, and the next write that works replaces the map
// and says so.

#include <signal.h>
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "firmware/survey_writer.hpp"
#include "hal/config/config_file.hpp"
#include "hal/config/map_file.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::firmware {
namespace {

using ::testing::HasSubstr;

// What the writer logs, as text.
class MemoryLog {
 public:
  MemoryLog() : file_(::open_memstream(&text_, &size_)) {}
  ~MemoryLog() {
    std::fclose(file_);
    std::free(text_);
  }
  std::FILE* file() { return file_; }
  std::string text() {
    std::fflush(file_);
    return std::string(text_, size_);
  }

 private:
  char* text_ = nullptr;
  std::size_t size_ = 0;
  std::FILE* file_;
};

TEST(SurveyWriter, AFailedMapWriteKeepsThePreviousMapAndIsTriedAgain) {
  test::TempDir dir;
  sim::write_synthetic_dataset(dir / "dataset", sim::SyntheticDatasetOptions{});
  std::ofstream(dir / "dataset" / "map.yaml", std::ios::app) << "    fixed: true\n";
  hal::RobotConfig config = hal::load_robot_config(dir / "dataset" / "config.yaml");
  config.setup.dot.observe_every_marker = true;
  Localizer localizer(std::move(config.setup));
  const std::filesystem::path output = dir / "surveyed.yaml";
  const std::string previous = "# the map of an earlier run\n" + test::read_text(dir / "dataset" / "map.yaml");
  std::ofstream(output) << previous;
  MemoryLog log;
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
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, previous_handler);
  EXPECT_TRUE(writer.last_write_failed());
  EXPECT_EQ(test::read_text(output), previous);
  EXPECT_EQ(log.text(), "irlocd: --survey " + output.string() +
                            ": cannot write the map (write): File too large: the previous map stays; trying again at "
                            "the next write\n");

  attempt_at(5);
  EXPECT_FALSE(writer.last_write_failed());
  EXPECT_THAT(log.text(), ::testing::EndsWith("irlocd: --survey " + output.string() + ": written again\n"));
  EXPECT_NE(test::read_text(output), previous);
  const MarkerMap map = hal::load_marker_map(output);
  ASSERT_EQ(map.dot_markers.size(), 1u);
  EXPECT_TRUE(map.dot_markers[0].fixed);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::AnyOf("dataset", "surveyed.yaml")) << "left behind";
  }
}

}  // namespace
}  // namespace irloc::firmware
