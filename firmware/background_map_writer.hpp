#pragma once
// Writes marker maps to one file on a thread of its own, so that the file's fsyncs (hundreds of
// milliseconds on a slow SD card) never hold up a frame. The frame loop hands over a map and goes
// on; a map handed over while the thread still writes the previous one replaces any other still
// waiting (the newest map is the one that matters). A write that fails leaves the file as it was
// (io::write_marker_map replaces it atomically) and is reported on `log` once, however often it
// fails again; the next write that works says so. The thread runs at normal priority whatever the
// frame loop's.

#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "algo/map/marker_map.hpp"
#include "io/files/map_file_writer.hpp"

namespace irloc::firmware {

class BackgroundMapWriter {
 public:
  // Writes a map to the file; throws io::InputError naming the file when it cannot.
  using WriteMap = std::function<void(const std::filesystem::path&, const MarkerMap&)>;

  // Each line on `log` is `log_prefix` followed by the error (which names the file) or by the
  // file's name. Starts the thread.
  BackgroundMapWriter(std::filesystem::path output, std::string log_prefix, std::FILE* log,
                      WriteMap write_map = io::write_marker_map);
  ~BackgroundMapWriter();  // writes the map still waiting, then stops the thread
  BackgroundMapWriter(const BackgroundMapWriter&) = delete;
  BackgroundMapWriter& operator=(const BackgroundMapWriter&) = delete;

  // Hands the map over and returns at once.
  void submit(MarkerMap map);
  // Waits until every map handed over is written (or has failed).
  void wait_until_written();
  // Whether the last write that ended failed (the file then holds an older map).
  bool last_write_failed();

 private:
  void run();
  void write(const MarkerMap& map);

  const std::filesystem::path output_;
  const std::string log_prefix_;
  std::FILE* log_;
  const WriteMap write_map_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<MarkerMap> waiting_;  // under mutex_
  bool writing_ = false;              // under mutex_
  bool stop_ = false;                 // under mutex_
  bool last_write_failed_ = false;    // under mutex_
  std::thread thread_;                // started last: it uses every member above
};

}  // namespace irloc::firmware
