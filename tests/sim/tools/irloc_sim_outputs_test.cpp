// irloc-sim's outputs under the one output-file policy (io/files/run_files.hpp), through the
// binary: no subcommand replaces its inputs (the picture tools their scenario, calibrate-mount its
// config or dataset), a path that cannot be written is refused before the work, and an empty file
// name is a usage error naming the option.

#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test::read_text;

class IrlocSimOutputs : public ::testing::Test {
 protected:
  test::ProcessResult irloc_sim(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), IRLOC_SIM_PATH);
    return test::run_to_end(std::move(arguments), dir_ / "stderr.txt");
  }
  // The run was refused with one line naming `flag` and `path` and saying `problem`.
  static void expect_refusal(const test::ProcessResult& run, const std::string& flag, const fs::path& path,
                             const std::string& problem) {
    EXPECT_EQ(run.status, 1) << run.stderr_text;
    EXPECT_EQ(std::count(run.stderr_text.begin(), run.stderr_text.end(), '\n'), 1) << run.stderr_text;
    EXPECT_THAT(run.stderr_text, HasSubstr("irloc-sim: error: " + flag + " " + path.string() + ": " + problem));
  }

  test::TempDir dir_;
};

TEST_F(IrlocSimOutputs, PictureToolsNeverReplaceTheirScenario) {
  const fs::path scenario = dir_ / "scenario.yaml";
  fs::copy_file(fs::path(IRLOC_SCENARIOS_DIR) / "led_landmarks_coverage.yaml", scenario);
  const std::string before = read_text(scenario);
  for (const char* tool : {"ledmap", "coverage", "ledplan"}) {
    SCOPED_TRACE(tool);
    expect_refusal(irloc_sim({tool, "--scenario", scenario.string(), "--out", scenario.string()}), "--out", scenario,
                   "is the input file " + scenario.string() + ": refusing to overwrite it");
    expect_refusal(irloc_sim({tool, "--scenario", scenario.string(), "--out", dir_.path().string()}), "--out",
                   dir_.path(), "is a folder, expected a file");
  }
  EXPECT_EQ(read_text(scenario), before);
  std::ofstream(dir_ / "map.yaml") << "dot_markers:\n  - {id: 1, origin: [0, 0, 2.5], yaw: 0, fixed: true}\n";
  expect_refusal(irloc_sim({"survey-map", "--drawing", (dir_ / "map.yaml").string(), "--estimate",
                            (dir_ / "map.yaml").string(), "--out", (dir_ / "map.yaml").string()}),
                 "--out", dir_ / "map.yaml", "is the input file");
}

TEST_F(IrlocSimOutputs, CalibrateMountNeverRewritesItsConfigOrDataset) {
  const fs::path dataset = dir_ / "spin";
  ASSERT_EQ(irloc_sim({"synth", "--out", dataset.string(), "--frames", "4"}).status, 0);
  const fs::path config = dataset / "config.yaml";
  const std::string before = read_text(config);
  const test::ProcessResult without_out = irloc_sim({"calibrate-mount", "--config", config.string(), "--dataset", dataset.string()});
  EXPECT_EQ(without_out.status, 2);
  EXPECT_THAT(without_out.stderr_text, HasSubstr("--out is required"));
  for (const char* input : {"config.yaml", "calib.yaml", "map.yaml", "frames.csv", "frame_000002.pgm"}) {
    expect_refusal(irloc_sim({"calibrate-mount", "--config", config.string(), "--dataset", dataset.string(), "--out",
                              (dataset / input).string()}),
                   "--out", dataset / input, "is the input file");
  }
  expect_refusal(irloc_sim({"calibrate-mount", "--config", config.string(), "--dataset", dataset.string(), "--out",
                            (config / "new.yaml").string()}),
                 "--out", config / "new.yaml", "lies under " + config.string() + ", which is no folder");
  EXPECT_EQ(read_text(config), before);
}

// A file the scenario names (calibration_file) is an input like the scenario; `run` does not
// remove a DIR/dataset holding its scenario.
TEST_F(IrlocSimOutputs, FilesTheScenarioNamesAndTheDatasetFolderAreProtected) {
  const fs::path scenario = dir_ / "dataset" / "scenario.yaml";
  fs::create_directories(scenario.parent_path());
  std::string text = read_text(fs::path(IRLOC_SCENARIOS_DIR) / "small_smoke.yaml");
  const std::size_t start = text.find("  calibration:");
  ASSERT_NE(start, std::string::npos);
  const std::size_t end = text.find("  mount:", start);
  ASSERT_NE(end, std::string::npos);
  std::ofstream(dir_ / "dataset" / "lens.yaml") << "image_width: 64\nimage_height: 48\ncamera_matrix: {rows: 3, cols: 3, data: "
                                                   "[40, 0, 31.5, 0, 40, 23.5, 0, 0, 1]}\ndistortion_model: plumb_bob\n"
                                                   "distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  text.replace(start, end - start, "  calibration_file: lens.yaml\n");
  std::ofstream(scenario) << text;
  const fs::path lens = dir_ / "dataset" / "lens.yaml";
  expect_refusal(irloc_sim({"ledmap", "--scenario", scenario.string(), "--out", lens.string()}), "--out", lens,
                 "is the input file " + lens.string() + ": refusing to overwrite it");
  expect_refusal(irloc_sim({"run", "--scenario", scenario.string(), "--out", dir_.path().string()}), "--out", dir_ / "dataset",
                 "holds the input file " + scenario.string() + ": refusing to replace the folder");
  EXPECT_TRUE(fs::exists(scenario));
  EXPECT_TRUE(fs::exists(lens));
}

TEST_F(IrlocSimOutputs, EmptyFileNamesAreUsageErrors) {
  const std::vector<std::vector<std::string>> runs = {
      {"render", "--scenario", "", "--out", (dir_ / "r").string()},
      {"ledmap", "--scenario", "x.yaml", "--out", ""},
      {"survey-map", "--drawing", "a.yaml", "--estimate", "b.yaml", "--truth", "", "--out", "c.png"},
      {"fit-confidence", "--config", "", "--dataset", "d"},
      {"plot-residuals", "--calibration", ""}};
  for (const std::vector<std::string>& run : runs) {
    const test::ProcessResult result = irloc_sim(run);
    EXPECT_EQ(result.status, 2) << run[0];
    EXPECT_THAT(result.stderr_text, HasSubstr("must not be empty")) << run[0];
  }
  EXPECT_FALSE(fs::exists(dir_ / "r"));
}

// A number option out of its finite range (docs/simulator.md): NaN, or a cell or colour scale so
// small the work would never end, is a usage error naming the option before any work.
TEST_F(IrlocSimOutputs, NumberOptionsOutOfTheirRangeAreUsageErrorsBeforeAnyWork) {
  const std::string scenario = std::string(IRLOC_SCENARIOS_DIR) + "/led_landmarks_coverage.yaml";
  const std::string out = (dir_ / "picture.png").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> runs = {
      {{"coverage", "--scenario", scenario, "--out", out, "--cell", "nan"}, "--cell"},
      {{"coverage", "--scenario", scenario, "--out", out, "--cell", "1e-6"}, "--cell"},
      {{"ledplan", "--scenario", scenario, "--out", out, "--cell", "1e-4"}, "--cell"},
      {{"ledmap", "--scenario", scenario, "--out", out, "--scale-max", "1e-300"}, "--scale-max"},
      {{"ledmap", "--scenario", scenario, "--out", out, "--half-extent", "inf"}, "--half-extent"}};
  for (const auto& [arguments, option] : runs) {
    const test::ProcessResult result = irloc_sim(arguments);
    EXPECT_EQ(result.status, 2) << arguments[0] << " " << option;
    // One message (CLI11's usage error, then its pointer to --help).
    const std::string first_line = result.stderr_text.substr(0, result.stderr_text.find('\n'));
    EXPECT_THAT(first_line, HasSubstr(option + ": must be a finite number in")) << result.stderr_text;
    EXPECT_FALSE(fs::exists(out)) << arguments[0];
  }
}

}  // namespace
}  // namespace irloc
