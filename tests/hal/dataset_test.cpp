#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <fstream>
#include <limits>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "algo/core/image.hpp"
#include "io/input_error.hpp"
#include "hal/replay/dataset_camera.hpp"
#include "io/dataset/dataset_writer.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"
#include "tests/support/text_file.hpp"

namespace irloc::hal {
namespace {

using ::testing::HasSubstr;
using test::read_text;
using io::DatasetWriter;

class Dataset : public ::testing::Test {
 protected:
  // Writes frames 0..count-1 of width x height, LED on for odd seq, pixel value = seq + x
  // (16-bit: 1000 seq + x, modulo 4096 to stay within maxval 4095).
  void write_frames(int count, bool sixteen_bit, int width = 5, int height = 3) {
    DatasetWriter writer(dir_.path(), 4095);
    Image8 image8(width, height);
    Image16 image16(width, height);
    for (int seq = 0; seq < count; ++seq) {
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          image8.view().at(x, y) = static_cast<std::uint8_t>(seq + x);
          image16.view().at(x, y) = static_cast<std::uint16_t>((1000 * seq + x) % 4096);
        }
      }
      Frame frame;
      frame.seq = static_cast<std::uint64_t>(seq);
      frame.t_ns = 5'000 + 100 * seq;
      frame.led_on = seq % 2 == 1;
      frame.image = sixteen_bit ? GrayImageView(ImageView16(image16.view())) : GrayImageView(ImageView8(image8.view()));
      writer.write(frame);
    }
  }
  std::string camera_error(int width = 5, int height = 3) {
    try {
      DatasetCamera camera(dir_.path(), width, height, "calib.yaml");
      Frame frame;
      while (camera.next(frame)) {
      }
    } catch (const io::InputError& e) {
      return e.what();
    }
    return "no error";
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // frame_000001.pgm as a 16-bit frame of maxval 4095 whose last pixel is `last`.
  void write_frames_16_bit_with_last_pixel(std::uint16_t last) {
    std::string pixels(30, '\0');
    pixels[28] = static_cast<char>(last >> 8);
    pixels[29] = static_cast<char>(last & 0xff);
    std::ofstream(path("frame_000000.pgm"), std::ios::binary) << "P5\n5 3\n4095\n" << std::string(30, '\0');
    std::ofstream(path("frame_000001.pgm"), std::ios::binary) << "P5\n5 3\n4095\n" << pixels;
  }

  test::TempDir dir_;
};

TEST_F(Dataset, RoundTripsEightAndSixteenBitFrames) {
  for (const bool sixteen_bit : {false, true}) {
    std::filesystem::remove_all(dir_.path());  // a dataset is written into a new folder
    write_frames(4, sixteen_bit);
    DatasetCamera camera(dir_.path(), 5, 3, "calib.yaml");
    EXPECT_EQ(camera.frame_count(), 4u);
    Frame frame;
    for (int seq = 0; seq < 4; ++seq) {
      ASSERT_TRUE(camera.next(frame));
      EXPECT_EQ(frame.seq, static_cast<std::uint64_t>(seq));
      EXPECT_EQ(frame.t_ns, 5'000 + 100 * seq);
      EXPECT_EQ(frame.led_on, seq % 2 == 1);
      if (sixteen_bit) {
        const auto& image = std::get<ImageView16>(frame.image);
        EXPECT_EQ(image.at(4, 2), 1000 * seq + 4);
      } else {
        const auto& image = std::get<ImageView8>(frame.image);
        EXPECT_EQ(image.at(4, 2), seq + 4);
      }
    }
    EXPECT_FALSE(camera.next(frame));
  }
}

TEST_F(Dataset, KeepsTheLastThreeFramesValid) {
  write_frames(5, false);
  DatasetCamera camera(dir_.path(), 5, 3, "calib.yaml");
  Frame frames[5];
  for (Frame& frame : frames) ASSERT_TRUE(camera.next(frame));
  for (int back = 0; back < 3; ++back) {
    const int seq = 4 - back;
    EXPECT_EQ(std::get<ImageView8>(frames[seq].image).at(0, 0), seq);
  }
}

TEST_F(Dataset, ReadsFramesWithoutAllocating) {
  write_frames(20, true);
  DatasetCamera camera(dir_.path(), 5, 3, "calib.yaml");
  Frame frame;
  int frames = 0;
  test::AllocationCounter counter;
  while (camera.next(frame)) ++frames;
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_EQ(frames, 20);
}

TEST_F(Dataset, NamesTheProblemInFramesCsv) {
  write_frames(3, false);
  const std::string index = path("frames.csv");
  std::ofstream(index) << "seq,t_ns,led,file\n0,100,0,frame_000000.pgm\n2,200,1,frame_000002.pgm\n1,300,0,frame_000001.pgm\n";
  EXPECT_EQ(camera_error(), index + ":4: seq: 1 does not increase (previous row has 2)");
  std::ofstream(index) << "seq,t_ns,led,file\n0,100,0,frame_000000.pgm\n1,100,1,frame_000001.pgm\n";
  EXPECT_EQ(camera_error(), index + ":3: t_ns: 100 does not increase (previous row has 100)");
  std::ofstream(index) << "seq,t_ns,led,file\n0,100,2,frame_000000.pgm\n";
  EXPECT_EQ(camera_error(), index + ":2: led: expected 0 or 1, got 2");
  std::ofstream(index) << "seq,time,led,file\n";
  EXPECT_EQ(camera_error(), index + ":1: expected the header seq,t_ns,led,file, got seq,time,led,file");
  std::ofstream(index) << "seq,t_ns,led,file\n0,100,0\n";
  EXPECT_EQ(camera_error(), index + ":2: expected 4 fields seq,t_ns,led,file, got 3");
  std::ofstream(index) << "seq,t_ns,led,file\n0,100,0,missing.pgm\n";
  EXPECT_EQ(camera_error(), index + ":2: file: cannot open " + path("missing.pgm") + ": No such file or directory");
  std::ofstream(index) << "seq,t_ns,led,file\n";
  EXPECT_EQ(camera_error(), index + ": no frames listed");
  std::filesystem::remove(index);
  EXPECT_EQ(camera_error(), index + ": cannot open: No such file or directory");
}

TEST_F(Dataset, NamesTheBadFrame) {
  write_frames(3, false);
  EXPECT_EQ(camera_error(6, 3), path("frame_000000.pgm") + ": frame is 5x3 but the calibration calib.yaml says 6x3");

  const std::string frame1 = path("frame_000001.pgm");
  std::string bytes = read_text(frame1);
  std::ofstream(frame1, std::ios::binary) << bytes.substr(0, bytes.size() - 4);
  EXPECT_EQ(camera_error(), frame1 + ": truncated: 15 bytes of pixels expected, 11 found");
  std::ofstream(frame1, std::ios::binary) << bytes << "xx";
  EXPECT_EQ(camera_error(), frame1 + ": unexpected data after the 15 bytes of pixels");
  std::ofstream(frame1, std::ios::binary) << "P5\n5 3\n1000\n" << std::string(30, '\0');
  EXPECT_EQ(camera_error(), frame1 + ": frame is 16-bit but the dataset's first frame is 8-bit");
}

TEST_F(Dataset, RefusesSpecialFilesWithoutBlocking) {
  write_frames(3, false);
  const std::string index = path("frames.csv");
  const std::string special = ": is a special file (FIFO, device or socket), expected a regular file";
  std::filesystem::remove(index);
  ASSERT_EQ(::mkfifo(index.c_str(), 0600), 0);  // would block forever in a plain open()
  EXPECT_EQ(camera_error(), index + special);
  std::filesystem::remove(index);
  std::filesystem::create_symlink("/dev/zero", index);  // would be read without end
  EXPECT_EQ(camera_error(), index + special);
  std::filesystem::remove(index);
  std::filesystem::create_directory(index);
  EXPECT_EQ(camera_error(), index + ": is a directory, expected a regular file");
  std::filesystem::remove(index);

  std::ofstream(index) << "seq,t_ns,led,file\n0,100,0,frame_000000.pgm\n1,200,1,frame_000001.pgm\n";
  const std::string frame1 = path("frame_000001.pgm");
  std::filesystem::remove(frame1);
  ASSERT_EQ(::mkfifo(frame1.c_str(), 0600), 0);
  EXPECT_EQ(camera_error(), index + ":3: file: " + frame1 + " is not a regular file");
}

TEST_F(Dataset, RefusesAFrameSwappedForAFifoAfterStartUp) {
  write_frames(3, false);
  DatasetCamera camera(dir_.path(), 5, 3, "calib.yaml");
  const std::string frame1 = path("frame_000001.pgm");
  std::filesystem::remove(frame1);
  ASSERT_EQ(::mkfifo(frame1.c_str(), 0600), 0);
  Frame frame;
  ASSERT_TRUE(camera.next(frame));
  EXPECT_EQ(test::input_error_message([&] { camera.next(frame); }),
            frame1 + ": is a special file (FIFO, device or socket), expected a regular file");
}

TEST_F(Dataset, RefusesANulByteInAFrameName) {
  write_frames(1, false);
  static constexpr char kIndex[] = "seq,t_ns,led,file\n0,100,0,frame_000000.pgm\0.x\n";
  std::ofstream(path("frames.csv"), std::ios::binary) << std::string(kIndex, sizeof kIndex - 1);
  EXPECT_EQ(camera_error(), path("frames.csv") + ":2: file: the name holds a NUL byte");
}

TEST_F(Dataset, RefusesPixelsAboveMaxval) {
  write_frames(2, false);
  const std::string frame1 = path("frame_000001.pgm");
  std::ofstream(frame1, std::ios::binary) << "P5\n5 3\n100\n" << std::string(14, '\x10') << '\xc8';
  EXPECT_EQ(camera_error(), frame1 + ": a pixel of 200 is above the header's maxval 100");
  write_frames_16_bit_with_last_pixel(4096);
  EXPECT_EQ(camera_error(), path("frame_000001.pgm") + ": a pixel of 4096 is above the header's maxval 4095");
}

TEST_F(Dataset, ChecksTheFrameSizeBeforeSizingBuffers) {
  write_frames(2, false);
  // A calibration of 16384 x 4096 would size buffers of hundreds of megabytes: refused first.
  EXPECT_EQ(test::input_error_message([&] { DatasetCamera(dir_.path(), 16384, 4096, "calib.yaml"); }),
            path("frame_000000.pgm") + ": frame is 5x3 but the calibration calib.yaml says 16384x4096");
}

TEST_F(Dataset, WriterRefusesAFolderInUseAndPlantedLinks) {
  write_frames(1, false);
  EXPECT_EQ(test::input_error_message([&] { DatasetWriter writer(dir_.path()); }),
            dir_.path().string() + ": the folder is not empty: give a new or empty folder (nothing is overwritten)");

  const std::filesystem::path fresh = dir_ / "fresh";
  DatasetWriter writer(fresh);
  const std::filesystem::path victim = dir_ / "victim.txt";
  std::ofstream(victim) << "keep me";
  std::filesystem::create_symlink(victim, fresh / "frame_000000.pgm");
  Image8 image(5, 3);
  EXPECT_EQ(test::input_error_message([&] { writer.write(Frame{0, 1, true, ImageView8(image.view())}); }),
            (fresh / "frame_000000.pgm").string() + ": cannot create: File exists");
  EXPECT_EQ(read_text(victim), "keep me");
}

// A file size limit stands in for a full disk. Whichever file fills (frames.csv, a frame), the
// folder stays a dataset of the frames written before: no partial PGM, no torn row.
TEST_F(Dataset, DiskFullLeavesADatasetOfTheWholeFrames) {
  rlimit saved{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  const auto previous_handler = ::signal(SIGXFSZ, SIG_IGN);
  std::string index_error;
  std::string frame_error;
  std::uint64_t frames_written = 0;
  {
    DatasetWriter writer(dir_.path(), 4095);
    rlimit small = saved;
    small.rlim_cur = 100;  // the 18-byte header and three 26-byte rows; a 5x3 PGM is 26 bytes
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
    Image8 image(5, 3);
    for (std::uint64_t seq = 0; seq < 10 && index_error.empty(); ++seq) {
      try {
        writer.write(Frame{seq, static_cast<std::int64_t>(5'000 + seq), false, ImageView8(image.view())});
      } catch (const io::InputError& e) {
        index_error = e.what();
      }
    }
    frames_written = writer.frames_written();
    Image8 large(20, 10);  // a 212-byte PGM
    try {
      writer.write(Frame{50, 6'000, false, ImageView8(large.view())});
    } catch (const io::InputError& e) {
      frame_error = e.what();
    }
  }
  ::setrlimit(RLIMIT_FSIZE, &saved);
  ::signal(SIGXFSZ, previous_handler);
  EXPECT_EQ(index_error, path("frames.csv") + ": cannot write: File too large");
  EXPECT_EQ(frame_error, path("frame_000050.pgm") + ": cannot write: File too large");
  EXPECT_EQ(frames_written, 3u);
  EXPECT_FALSE(std::filesystem::exists(path("frame_000003.pgm")));
  EXPECT_FALSE(std::filesystem::exists(path("frame_000050.pgm")));
  EXPECT_EQ(read_text(path("frames.csv")), "seq,t_ns,led,file\n0,5000,0,frame_000000.pgm\n1,5001,0,frame_000001.pgm\n"
                                           "2,5002,0,frame_000002.pgm\n");
  DatasetCamera camera(dir_.path(), 5, 3, "calib.yaml");
  EXPECT_EQ(camera.frame_count(), 3u);
  Frame frame;
  for (std::uint64_t seq = 0; seq < 3; ++seq) {
    ASSERT_TRUE(camera.next(frame));
    EXPECT_EQ(frame.seq, seq);
  }
  EXPECT_FALSE(camera.next(frame));
}

}  // namespace
}  // namespace irloc::hal
