// The one output-file policy (io::RunFiles) and the one temporary-file helper
// (io::replace_file_atomically), class by class: outputs that would destroy an input or another
// output, special files and links, paths that cannot be written (found before any work), and
// what a failed or killed write leaves behind.

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/files/output_file.hpp"
#include "io/files/run_files.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::io {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using test::input_error_message;
using test::read_text;

class RunFilesTest : public ::testing::Test {
 protected:
  RunFilesTest() {
    std::ofstream(input()) << "robot: {dof: 3}\n";
    fs::create_directory(dir_ / "sub");
  }
  fs::path input() const { return dir_ / "config.yaml"; }
  // The message of the refusal of `output` as --stats in a run that reads input().
  std::string refusal_of(const fs::path& output) const {
    RunFiles files;
    files.input(input());
    files.output_file("--stats", output);
    return input_error_message([&] { files.check(); });
  }

  test::TempDir dir_;
};

TEST_F(RunFilesTest, AnInputIsRefusedByAnyPathOrHardLink) {
  const std::string expected = ": is the input file " + input().string() + ": refusing to overwrite it";
  EXPECT_EQ(refusal_of(input()), "--stats " + input().string() + expected);
  const fs::path roundabout = dir_ / "sub" / ".." / "config.yaml";
  EXPECT_EQ(refusal_of(roundabout), "--stats " + roundabout.string() + expected);
  fs::create_hard_link(input(), dir_ / "hard.json");
  EXPECT_EQ(refusal_of(dir_ / "hard.json"), "--stats " + (dir_ / "hard.json").string() + expected);
  EXPECT_EQ(read_text(input()), "robot: {dof: 3}\n");
}

TEST_F(RunFilesTest, TwoOutputsOnOneFileAreRefused) {
  RunFiles files;
  files.output_file("--pose-csv", dir_ / "out.csv");
  files.output_file("--survey", dir_ / "sub" / ".." / "out.csv");
  EXPECT_EQ(input_error_message([&] { files.check(); }),
            "--survey " + (dir_ / "sub" / ".." / "out.csv").string() + ": is also the output of --pose-csv " +
                (dir_ / "out.csv").string() + ": give each output a file of its own");
  RunFiles into_new_folder;
  into_new_folder.new_folder("--record", dir_ / "recording");
  into_new_folder.output_file("--pose-csv", dir_ / "recording" / "pose.csv");
  EXPECT_THAT(input_error_message([&] { into_new_folder.check(); }), HasSubstr("lies in the new folder of --record"));
  RunFiles two_folders;
  two_folders.new_folder("--record", dir_ / "recording");
  two_folders.output_folder("--calibrate", dir_ / "recording" / "calibration", {"calib.yaml"});
  EXPECT_THAT(input_error_message([&] { two_folders.check(); }), HasSubstr("lies in the new folder of --record"));
}

TEST_F(RunFilesTest, SpecialFilesFoldersAndLinksAreRefused) {
  ASSERT_EQ(::mkfifo((dir_ / "fifo").c_str(), 0600), 0);
  EXPECT_THAT(refusal_of(dir_ / "fifo"), HasSubstr("is a special file (FIFO, device or socket): refusing to replace it"));
  EXPECT_THAT(refusal_of("/dev/null"), HasSubstr("is a special file"));
  EXPECT_THAT(refusal_of(dir_ / "sub"), HasSubstr("is a folder, expected a file"));
  EXPECT_THAT(refusal_of(dir_ / "."), HasSubstr("names a folder, expected a file name"));
  fs::create_symlink(dir_ / "elsewhere.json", dir_ / "link.json");  // dangling: its target would be created
  EXPECT_THAT(refusal_of(dir_ / "link.json"), HasSubstr("is a symbolic link: refusing to replace it or write through it"));
  EXPECT_FALSE(fs::exists(dir_ / "elsewhere.json"));
}

TEST_F(RunFilesTest, UnwritablePathsAreRefusedBeforeAnyWork) {
  EXPECT_EQ(refusal_of(input() / "stats.json"),
            "--stats " + (input() / "stats.json").string() + ": lies under " + input().string() + ", which is no folder");
  EXPECT_EQ(refusal_of(dir_ / "missing" / "stats.json"),
            "--stats " + (dir_ / "missing" / "stats.json").string() + ": its folder " + (dir_ / "missing").string() +
                " does not exist");
  const long name_max = ::pathconf(dir_.path().c_str(), _PC_NAME_MAX);
  ASSERT_GT(name_max, 8);
  // The longest legal name, whose temporary name would not be.
  const fs::path long_name = dir_ / std::string(static_cast<std::size_t>(name_max) - 1, 'm');
  EXPECT_THAT(refusal_of(long_name), HasSubstr("the file name is too long: its temporary file (.NAME.XXXXXX) needs"));
  EXPECT_NO_THROW({
    RunFiles files;
    files.output_file("--stats", dir_ / std::string(static_cast<std::size_t>(name_max) - kTemporaryNameExtra, 'm'));
    files.check();
  });
  RunFiles folder_under_file;
  folder_under_file.output_folder("--calibrate", input() / "calibration", {"calib.yaml"});
  EXPECT_THAT(input_error_message([&] { folder_under_file.check(); }), HasSubstr("which is no folder"));
  if (::geteuid() != 0) {  // root writes anywhere
    fs::create_directory(dir_ / "read_only");
    fs::permissions(dir_ / "read_only", fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THAT(refusal_of(dir_ / "read_only" / "stats.json"), HasSubstr("cannot write in its folder"));
  }
}

TEST_F(RunFilesTest, FolderOutputsCheckTheirFilesAgainstTheInputs) {
  RunFiles files;
  files.input(input());
  files.output_folder("--calibrate", dir_.path(), {"calib.yaml", "config.yaml"});
  EXPECT_EQ(input_error_message([&] { files.check(); }),
            "--calibrate " + (dir_.path() / "config.yaml").string() + ": is the input file " + input().string() +
                ": refusing to overwrite it");
  RunFiles not_empty;
  not_empty.new_folder("--record", dir_.path());
  EXPECT_THAT(input_error_message([&] { not_empty.check(); }), HasSubstr("the folder is not empty"));
  RunFiles fine;
  fine.input(input());
  fine.output_folder("--calibrate", dir_ / "new" / "calibration", {"calib.yaml", "config.yaml"});
  fine.new_folder("--record", dir_ / "recording");
  fine.output_file("--pose-csv", dir_ / "pose.csv");
  EXPECT_NO_THROW(fine.check());
  EXPECT_FALSE(fs::exists(dir_ / "new"));  // checking writes nothing
}

// A folder the run removes and writes anew (irloc-sim run's DIR/dataset) may hold no input and
// may not be a link to somewhere else.
TEST_F(RunFilesTest, AReplacedFolderHoldsNoInputAndIsNoLink) {
  fs::create_directory(dir_ / "dataset");
  std::ofstream(dir_ / "dataset" / "scenario.yaml") << "frames: 2\n";
  RunFiles holds_input;
  holds_input.input(dir_ / "sub" / ".." / "dataset" / "scenario.yaml");
  holds_input.replaced_folder("--out", dir_ / "dataset");
  EXPECT_EQ(input_error_message([&] { holds_input.check(); }),
            "--out " + (dir_ / "dataset").string() + ": holds the input file " +
                (dir_ / "sub" / ".." / "dataset" / "scenario.yaml").string() + ": refusing to replace the folder");
  fs::create_directory_symlink(dir_ / "sub", dir_ / "linked");
  RunFiles link;
  link.replaced_folder("--out", dir_ / "linked");
  EXPECT_THAT(input_error_message([&] { link.check(); }), HasSubstr("is a symbolic link: refusing to replace what it points to"));
  RunFiles fine;
  fine.input(input());
  fine.replaced_folder("--out", dir_ / "dataset");
  fine.replaced_folder("--out", dir_ / "absent");
  EXPECT_NO_THROW(fine.check());
  EXPECT_TRUE(fs::exists(dir_ / "dataset" / "scenario.yaml"));  // checking removes nothing
}

TEST_F(RunFilesTest, StaleTemporariesOfAKilledRunAreRemovedByTheNextOne) {
  std::ofstream(dir_ / ".map.yaml.Ab3xYz") << "half a map";
  std::ofstream(dir_ / ".map.yaml.keep") << "not a temporary of map.yaml";
  std::ofstream(dir_ / ".other.yaml.Ab3xYz") << "another file's";
  RunFiles files;
  files.output_file("--survey", dir_ / "map.yaml");
  files.check();
  EXPECT_FALSE(fs::exists(dir_ / ".map.yaml.Ab3xYz"));
  EXPECT_TRUE(fs::exists(dir_ / ".map.yaml.keep"));
  EXPECT_TRUE(fs::exists(dir_ / ".other.yaml.Ab3xYz"));
}

// Everything in the folder but `kept`.
std::vector<std::string> other_files(const fs::path& dir, const std::string& kept) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename() != kept) names.push_back(entry.path().filename().string());
  }
  return names;
}

TEST(ReplaceFileAtomically, WritesAUniqueTemporaryNeverAFixedNameOrALink) {
  test::TempDir dir;
  // A planted FILE.tmp link (the old fixed name) is neither followed nor replaced.
  std::ofstream(dir / "victim") << "victim";
  fs::create_symlink(dir / "victim", dir / "stats.json.tmp");
  replace_file_atomically(dir / "stats.json", "{}\n");
  EXPECT_EQ(read_text(dir / "stats.json"), "{}\n");
  EXPECT_EQ(read_text(dir / "victim"), "victim");
  EXPECT_TRUE(fs::is_symlink(dir / "stats.json.tmp"));
  EXPECT_EQ(fs::status(dir / "stats.json").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
  // Refused at the write too, when something else took the file's place since the start.
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  EXPECT_EQ(input_error_message([&] { replace_file_atomically(dir / "fifo", "x", 0644, "the statistics"); }),
            (dir / "fifo").string() + ": cannot write the statistics: is no regular file: refusing to replace it");
}

// A file size limit stands in for a full disk.
TEST(ReplaceFileAtomically, AFullDiskKeepsTheOldFileWholeAndLeavesNoTemporary) {
  test::TempDir dir;
  std::ofstream(dir / "map.yaml") << "old: map\n";
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto previous_handler = ::signal(SIGXFSZ, SIG_IGN);
  rlimit small = saved;
  small.rlim_cur = 100;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string message =
      input_error_message([&] { replace_file_atomically(dir / "map.yaml", std::string(1000, 'x'), 0644, "the map"); });
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, previous_handler);
  EXPECT_THAT(message, StartsWith((dir / "map.yaml").string() + ": cannot write the map (write): "));
  EXPECT_THAT(message, HasSubstr("File too large"));
  EXPECT_EQ(read_text(dir / "map.yaml"), "old: map\n");
  EXPECT_THAT(other_files(dir.path(), "map.yaml"), ::testing::IsEmpty());
}

}  // namespace
}  // namespace irloc::io
