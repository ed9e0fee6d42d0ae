// irlocd --survey MAP_OUT on the synthetic replay dataset (one dot marker): the map is written
// and reads back, the fixed marker unchanged; bad set-ups end with one line naming the file.

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/map_file.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/file_size_limited_run.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

using ::testing::HasSubstr;

class IrlocdSurvey : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SyntheticDatasetOptions options;
    options.frames = 20;
    sim::write_synthetic_dataset(dataset(), options);
  }
  std::filesystem::path dataset() const { return dir_ / "dataset"; }
  std::filesystem::path map_out() const { return dir_ / "surveyed.yaml"; }

  void fix_the_marker() {
    std::string map = test::read_text(dataset() / "map.yaml");
    map += "    fixed: true\n";
    std::ofstream(dataset() / "map.yaml") << map;
  }
  // The survey arguments of a replay writing `output`.
  std::vector<std::string> survey_arguments(const std::filesystem::path& output) const {
    return {IRLOCD_PATH, "--config", (dataset() / "config.yaml").string(), "--camera", "dir:" + dataset().string(),
            "--serial", "none", "--survey", output.string()};
  }
  // Exit status and stderr of a survey replay writing `output`.
  test::ProcessResult survey(const std::filesystem::path& output) {
    return test::run_to_end(survey_arguments(output), dir_ / "stderr.txt");
  }

  test::TempDir dir_;
};

TEST_F(IrlocdSurvey, WritesAMapThatReadsBackWithTheFixedMarkerUnchanged) {
  fix_the_marker();
  const auto [status, errors] = survey(map_out());
  ASSERT_EQ(status, 0) << errors;
  const MarkerMap map = io::load_marker_map(map_out());
  ASSERT_EQ(map.dot_markers.size(), 1u);
  EXPECT_EQ(map.dot_markers[0].id, 1782);
  EXPECT_TRUE(map.dot_markers[0].fixed);
  EXPECT_EQ(map.dot_markers[0].origin, Eigen::Vector3d(1.0, 2.0, 2.6));
}

TEST_F(IrlocdSurvey, AMapWithoutAFixedMarkerIsAnInputError) {
  const auto [status, errors] = survey(map_out());
  EXPECT_EQ(status, 1);
  EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
  EXPECT_THAT(errors, HasSubstr((dataset() / "map.yaml").string() + ": dot_markers: --survey needs one with `fixed: true`"));
  EXPECT_FALSE(std::filesystem::exists(map_out()));
}

TEST_F(IrlocdSurvey, AnUnwritableOutputIsAnErrorNamingIt) {
  fix_the_marker();
  const std::filesystem::path output = dir_ / "no-such-folder" / "map.yaml";
  const auto [status, errors] = survey(output);
  EXPECT_EQ(status, 1);
  EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
  EXPECT_THAT(errors, HasSubstr("--survey " + output.string() + ": its folder " + (dir_ / "no-such-folder").string() +
                                " does not exist"));
}

// The disk is full (every file limited to 64 bytes, less than a map) through a survey of 700
// frames, whose map is written at 10 s and 20 s of frame time and at the end: the map written by
// an earlier run stays as it was, no temporary file is left, one line says so, and the exit
// status says that the map lacks this run.
TEST_F(IrlocdSurvey, AFullDiskKeepsThePreviousMapAndSaysSoOnce) {
  sim::SyntheticDatasetOptions options;
  options.width = 64;
  options.height = 48;
  options.frames = 700;
  std::filesystem::remove_all(dataset());
  sim::write_synthetic_dataset(dataset(), options);
  fix_the_marker();
  const std::string previous = test::read_text(dataset() / "map.yaml") + "# the map of an earlier run\n";
  std::ofstream(map_out()) << previous;
  const test::ProcessResult run = test::run_with_file_size_limit(survey_arguments(map_out()), 64);
  EXPECT_EQ(run.status, 1) << run.stderr_text;
  const std::string failed = "irlocd: --survey " + map_out().string() +
                             ": cannot write the map (write): File too large: the previous map stays; trying again at "
                             "the next write\n";
  EXPECT_THAT(run.stderr_text, HasSubstr(failed));
  EXPECT_EQ(run.stderr_text.find(failed), run.stderr_text.rfind(failed)) << run.stderr_text;
  EXPECT_THAT(run.stderr_text, HasSubstr("irlocd: 700 frames, 350 pose attempts"));
  EXPECT_THAT(run.stderr_text, HasSubstr("; an output failed (above): data was lost\n"));
  EXPECT_EQ(test::read_text(map_out()), previous);
  EXPECT_EQ(io::load_marker_map(map_out()).dot_markers.size(), 1u);
  for (const auto& entry : std::filesystem::directory_iterator(dir_.path())) {
    EXPECT_THAT(entry.path().filename().string(), ::testing::AnyOf("dataset", "surveyed.yaml")) << "left behind";
  }
}

}  // namespace
}  // namespace irloc
