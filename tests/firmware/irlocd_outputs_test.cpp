// irlocd's outputs under the one output-file policy (io/files/run_files.hpp), run as a user runs
// it, one test per class of harm: no output replaces an input, another output, a special file or
// a link; a path that cannot be written is refused before the drive, with nothing written; and a
// closed stderr costs no output.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <map>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/map_file.hpp"
#include "host_sim/render/synthetic_dataset.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using test::ProcessResult;
using test::read_text;

// The flags that write one file.
constexpr const char* kFileOutputs[] = {"--pose-csv", "--stats", "--survey"};

class IrlocdOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    sim::SyntheticDatasetOptions options;
    options.frames = 8;
    sim::write_synthetic_dataset(dataset(), options);
    std::ofstream(dataset() / "map.yaml", std::ios::app) << "    fixed: true\n";  // a survey may run
  }
  fs::path dataset() const { return dir_ / "dataset"; }

  ProcessResult replay_with(const std::vector<std::string>& more) {
    std::vector<std::string> arguments = {IRLOCD_PATH, "--config", (dataset() / "config.yaml").string(), "--camera",
                                          "dir:" + dataset().string(), "--serial", "none"};
    arguments.insert(arguments.end(), more.begin(), more.end());
    return test::run_to_end(std::move(arguments), dir_ / "stderr.txt");
  }
  // The run was refused with exactly one line naming `flag` and `path` and saying `problem`.
  static void expect_refusal(const ProcessResult& run, const std::string& flag, const fs::path& path,
                             const std::string& problem) {
    EXPECT_EQ(run.status, 1) << run.stderr_text;
    EXPECT_EQ(std::count(run.stderr_text.begin(), run.stderr_text.end(), '\n'), 1) << run.stderr_text;
    EXPECT_THAT(run.stderr_text, HasSubstr("irlocd: error: " + flag + " " + path.string() + ": "));
    EXPECT_THAT(run.stderr_text, HasSubstr(problem));
  }
  // Every file of the dataset, by name, with its content.
  std::map<std::string, std::string> dataset_contents() const {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(dataset())) files[entry.path().filename()] = read_text(entry.path());
    return files;
  }

  test::TempDir dir_;
};

TEST_F(IrlocdOutputs, NoOutputReplacesAnInput) {
  const std::map<std::string, std::string> before = dataset_contents();
  for (const std::string output : kFileOutputs) {
    for (const char* input : {"config.yaml", "calib.yaml", "map.yaml", "frames.csv", "frame_000002.pgm"}) {
      SCOPED_TRACE(output + " " + input);
      expect_refusal(replay_with({output, (dataset() / input).string()}), output, dataset() / input,
                     "is the input file " + (dataset() / input).string() + ": refusing to overwrite it");
    }
  }
  // The live view's token off loopback is read at start (made when absent): no output replaces it.
  const fs::path token = dir_ / "http-token";
  std::ofstream(token) << "0123456789abcdef0123\n";
  fs::permissions(token, fs::perms::owner_read | fs::perms::owner_write);
  for (const std::string output : kFileOutputs) {
    SCOPED_TRACE(output + " the token");
    expect_refusal(replay_with({"--http", "0.0.0.0:18431", "--http-token", token.string(), output, token.string()}), output,
                   token, "is the input file " + token.string() + ": refusing to overwrite it");
  }
  EXPECT_EQ(read_text(token), "0123456789abcdef0123\n");
  // --calibrate into the dataset's folder would replace its config.yaml and calib.yaml.
  expect_refusal(replay_with({"--calibrate", dataset().string()}), "--calibrate", dataset() / "calib.yaml",
                 "is the input file");
  EXPECT_EQ(dataset_contents(), before);
}

TEST_F(IrlocdOutputs, NoOutputReplacesAnotherOutputASpecialFileOrALink) {
  const fs::path shared = dir_ / "out.txt";
  expect_refusal(replay_with({"--pose-csv", shared.string(), "--survey", shared.string()}), "--survey", shared,
                 "is also the output of --pose-csv " + shared.string());
  expect_refusal(replay_with({"--stats", shared.string(), "--survey", (dir_ / "." / "out.txt").string()}), "--stats",
                 shared, "is also the output of --survey " + (dir_ / "." / "out.txt").string());
  EXPECT_FALSE(fs::exists(shared));

  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);  // nobody reads it: a write would block
  std::ofstream(dir_ / "victim.yaml") << "victim\n";
  fs::create_symlink(dir_ / "victim.yaml", dir_ / "link.yaml");
  for (const std::string output : kFileOutputs) {
    SCOPED_TRACE(output);
    expect_refusal(replay_with({output, (dir_ / "fifo").string()}), output, dir_ / "fifo",
                   "is a special file (FIFO, device or socket)");
    expect_refusal(replay_with({output, (dir_ / "link.yaml").string()}), output, dir_ / "link.yaml",
                   "is a symbolic link");
  }
  EXPECT_EQ(fs::status(dir_ / "fifo").type(), fs::file_type::fifo);
  EXPECT_TRUE(fs::is_symlink(dir_ / "link.yaml"));
  EXPECT_EQ(read_text(dir_ / "victim.yaml"), "victim\n");
}

// What used to be found only after the whole drive, when the survey was lost.
TEST_F(IrlocdOutputs, AnUnwritableOutputIsRefusedBeforeTheDriveWithNothingWritten) {
  std::ofstream(dir_ / "regular") << "a file\n";
  fs::create_directory(dir_ / "folder");
  const long name_max = ::pathconf(dir_.path().c_str(), _PC_NAME_MAX);
  const fs::path long_name = dir_ / std::string(static_cast<std::size_t>(name_max) - 1, 'm');
  const fs::path pose_csv = dir_ / "pose.csv";
  const struct {
    fs::path path;
    std::string problem;
  } cases[] = {{dir_ / "folder", "is a folder, expected a file"},
               {dir_ / "regular" / "map.yaml", "lies under " + (dir_ / "regular").string() + ", which is no folder"},
               {dir_ / "missing" / "map.yaml", "does not exist"},
               {long_name, "the file name is too long: its temporary file"}};
  for (const auto& bad : cases) {
    for (const std::string output : kFileOutputs) {
      if (output == "--pose-csv") continue;  // the good output below
      SCOPED_TRACE(output + " " + bad.path.string());
      expect_refusal(replay_with({"--pose-csv", pose_csv.string(), output, bad.path.string()}), output,
                     bad.path, bad.problem);
      EXPECT_FALSE(fs::exists(pose_csv));
    }
  }
  expect_refusal(replay_with({"--calibrate", (dir_ / "regular" / "calibration").string()}), "--calibrate",
                 dir_ / "regular" / "calibration", "which is no folder");
}

// A survey whose stderr is a pipe nobody reads any more still writes its map; a stale temporary
// of a killed earlier survey is removed.
TEST_F(IrlocdOutputs, AClosedStderrCostsNoMapAndStaleTemporariesAreRemoved) {
  ::signal(SIGPIPE, SIG_DFL);  // as a shell starts it (an ignored SIGPIPE would be inherited)
  const fs::path map = dir_ / "surveyed.yaml";
  std::ofstream(dir_ / ".surveyed.yaml.k9Ll3d") << "what a killed survey left";
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  ::close(pipe_fds[0]);  // every write to stderr: EPIPE (and SIGPIPE, unless ignored)
  test::ChildOptions options;
  options.fds = {{pipe_fds[1], STDERR_FILENO}};
  test::ChildProcess irlocd({IRLOCD_PATH, "--config", (dataset() / "config.yaml").string(), "--camera",
                             "dir:" + dataset().string(), "--serial", "none", "--survey", map.string()},
                            options);
  ::close(pipe_fds[1]);
  EXPECT_EQ(irlocd.wait(), 0);
  EXPECT_EQ(io::load_marker_map(map).dot_markers.size(), 1u);
  EXPECT_FALSE(fs::exists(dir_ / ".surveyed.yaml.k9Ll3d"));
}

}  // namespace
}  // namespace irloc
