// io/files/pose_csv_writer: the pose CSV of the spec, written without allocating; a special file
// refused; a full disk leaves whole rows.

#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/files/pose_csv_writer.hpp"
#include "io/input_error.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using test::read_text;

TEST(PoseCsvWriter, WritesTheSpecRowsWithoutAllocating) {
  test::TempDir dir;
  {
    PoseCsvWriter writer(dir / "pose.csv");
    PoseEstimate ok;
    ok.seq = 7;
    ok.t_ns = 123456789012;
    ok.ok = true;
    ok.x = 1.25;
    ok.y = -0.5;
    ok.z = 0;
    ok.yaw = -3.14159265;
    ok.marker_id = 1782;
    ok.confidence = 0.98765;
    PoseEstimate none;
    none.seq = 9;
    none.t_ns = 123456789013;
    none.source = SourceKind::square;
    test::AllocationCounter counter;
    writer.write(ok);
    writer.write(none);
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_EQ(read_text(dir / "pose.csv"),
            "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source\n"
            "7,123456789012,ok,1.250000,-0.500000,0.000000,0.000000,0.000000,-3.141593,1782,0.9877,dot\n"
            "9,123456789013,none,,,,,,,-1,0,square\n");
}

TEST(PoseCsvWriter, PrintsSeqAbove2To63Unsigned) {
  test::TempDir dir;
  {
    PoseCsvWriter writer(dir / "pose.csv");
    PoseEstimate none;
    none.seq = std::numeric_limits<std::uint64_t>::max();
    writer.write(none);
  }
  EXPECT_THAT(read_text(dir / "pose.csv"), HasSubstr("\n18446744073709551615,0,none,"));
}

// What else an output may not be (an input, another output) is io::RunFiles' check
// (run_files_test.cpp); the writer itself never writes through a link or into a special file.
TEST(PoseCsvWriter, RefusesALinkOrASpecialFile) {
  test::TempDir dir;
  std::ofstream(dir / "config.yaml") << "robot: {dof: 3}\n";
  std::filesystem::create_symlink(dir / "config.yaml", dir / "link.csv");
  EXPECT_THAT(test::input_error_message([&] { PoseCsvWriter(dir / "link.csv"); }),
              StartsWith((dir / "link.csv").string() + ": cannot write: "));
  EXPECT_EQ(read_text(dir / "config.yaml"), "robot: {dof: 3}\n");
  ASSERT_EQ(::mkfifo((dir / "fifo.csv").c_str(), 0600), 0);  // no reader: a blocking open would hang
  EXPECT_EQ(test::input_error_message([&] { PoseCsvWriter(dir / "fifo.csv"); }),
            (dir / "fifo.csv").string() + ": is no regular file: refusing to write the pose CSV to it");
}

// A file size limit stands in for a full disk: the write that crosses it is short, the next fails.
TEST(PoseCsvWriter, DiskFullLeavesOnlyWholeRows) {
  test::TempDir dir;
  const std::filesystem::path file = dir / "pose.csv";
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto previous_handler = ::signal(SIGXFSZ, SIG_IGN);
  std::string error;
  {
    PoseCsvWriter writer(file);
    const std::size_t limit = std::string(PoseCsvWriter::kHeader).size() + 1 + 60;  // header + 1.x rows
    rlimit small = saved;
    small.rlim_cur = limit;
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    PoseEstimate none;
    for (std::uint64_t seq = 1; seq <= 10 && error.empty(); ++seq) {
      none.seq = seq;
      try {
        writer.write(none);
      } catch (const io::InputError& e) {
        error = e.what();
      }
    }
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, previous_handler);
  EXPECT_EQ(error, file.string() + ": cannot write: File too large");
  const std::string text = read_text(file);
  EXPECT_EQ(text.back(), '\n');
  EXPECT_EQ(text, std::string(PoseCsvWriter::kHeader) + "\n1,0,none,,,,,,,-1,0,dot\n2,0,none,,,,,,,-1,0,dot\n");
}

TEST(PoseCsvWriter, NamesAnUnwritableFile) {
  try {
    PoseCsvWriter writer("/nonexistent-dir/pose.csv");
    FAIL() << "no error";
  } catch (const io::InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent-dir/pose.csv: cannot write"));
  }
}

}  // namespace
}  // namespace irloc::io
