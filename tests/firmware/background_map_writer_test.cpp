// BackgroundMapWriter with a stand-in for the file write: handing a map over returns while the
// write of the one before is held up (a slow SD card), the newest map replaces one still waiting,
// a failing write is reported once and its recovery once, and the map still waiting when the
// writer goes is written.

#include <condition_variable>
#include <mutex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "firmware/background_map_writer.hpp"
#include "io/input_error.hpp"
#include "tests/support/memory_log.hpp"

namespace irloc::firmware {
namespace {

// A map told apart by its one dot marker's ID.
MarkerMap map_with(int id) {
  MarkerMap map;
  DotMarker marker;
  marker.id = id;
  marker.origin = Eigen::Vector3d(0.1 * id, 0, 2.5);
  map.dot_markers.push_back(marker);
  return map;
}

// The stand-in disk: records the maps written (by ID); while held, a write waits until released.
class SlowDisk {
 public:
  BackgroundMapWriter::WriteMap writer() {
    return [this](const std::filesystem::path& path, const MarkerMap& map) {
      std::unique_lock lock(mutex_);
      ++started_;
      changed_.notify_all();
      changed_.wait(lock, [this] { return !held_; });
      if (failures_left_ > 0) {
        --failures_left_;
        throw io::InputError(path.string() + ": cannot write the map (write): No space left on device");
      }
      written_.push_back(map.dot_markers.at(0).id);
    };
  }
  void hold() { set_held(true); }
  void release() { set_held(false); }
  void fail_next(int writes) {
    const std::lock_guard lock(mutex_);
    failures_left_ = writes;
  }
  void wait_until_started(int writes) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return started_ >= writes; });
  }
  std::vector<int> written() {
    const std::lock_guard lock(mutex_);
    return written_;
  }

 private:
  void set_held(bool held) {
    {
      const std::lock_guard lock(mutex_);
      held_ = held;
    }
    changed_.notify_all();
  }
  std::mutex mutex_;
  std::condition_variable changed_;
  bool held_ = false;
  int started_ = 0, failures_left_ = 0;
  std::vector<int> written_;
};

TEST(BackgroundMapWriter, HandingAMapOverReturnsWhileASlowWriteLastsAndTheNewestWaitingMapIsWritten) {
  SlowDisk disk;
  test::MemoryLog log;
  BackgroundMapWriter writer("map.yaml", "test: ", log.file(), disk.writer());
  disk.hold();
  writer.submit(map_with(1));
  disk.wait_until_started(1);  // map 1's write is under way and held
  writer.submit(map_with(2));  // returns: the frame loop goes on
  writer.submit(map_with(3));  // replaces map 2, which never began
  EXPECT_TRUE(disk.written().empty());
  disk.release();
  writer.wait_until_written();
  EXPECT_EQ(disk.written(), (std::vector<int>{1, 3}));
  EXPECT_FALSE(writer.last_write_failed());
  EXPECT_EQ(log.text(), "");
}

TEST(BackgroundMapWriter, AFailingWriteIsReportedOnceAndSoIsTheWriteThatWorksAgain) {
  SlowDisk disk;
  test::MemoryLog log;
  BackgroundMapWriter writer("out/map.yaml", "test: ", log.file(), disk.writer());
  disk.fail_next(3);
  for (int id = 1; id <= 3; ++id) {
    writer.submit(map_with(id));
    writer.wait_until_written();
    EXPECT_TRUE(writer.last_write_failed()) << "map " << id;
  }
  EXPECT_EQ(log.text(), "test: out/map.yaml: cannot write the map (write): No space left on device: the previous map "
                        "stays; trying again at the next write\n");
  writer.submit(map_with(4));
  writer.wait_until_written();
  EXPECT_FALSE(writer.last_write_failed());
  EXPECT_EQ(disk.written(), std::vector<int>{4});
  EXPECT_EQ(log.text(), "test: out/map.yaml: cannot write the map (write): No space left on device: the previous map "
                        "stays; trying again at the next write\ntest: out/map.yaml: written again\n");
}

TEST(BackgroundMapWriter, TheMapStillWaitingWhenTheWriterGoesIsWritten) {
  SlowDisk disk;
  test::MemoryLog log;
  {
    BackgroundMapWriter writer("map.yaml", "test: ", log.file(), disk.writer());
    disk.hold();
    writer.submit(map_with(1));
    disk.wait_until_started(1);
    writer.submit(map_with(2));
    disk.release();
  }
  EXPECT_EQ(disk.written(), (std::vector<int>{1, 2}));
}

}  // namespace
}  // namespace irloc::firmware
