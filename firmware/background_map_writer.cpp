#include "firmware/background_map_writer.hpp"

#include <pthread.h>
#include <sched.h>

#include <utility>

#include "io/input_error.hpp"

namespace irloc::firmware {

BackgroundMapWriter::BackgroundMapWriter(std::filesystem::path output, std::string log_prefix, std::FILE* log,
                                         WriteMap write_map)
    : output_(std::move(output)),
      log_prefix_(std::move(log_prefix)),
      log_(log),
      write_map_(std::move(write_map)),
      thread_([this] { run(); }) {}

BackgroundMapWriter::~BackgroundMapWriter() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void BackgroundMapWriter::submit(MarkerMap map) {
  {
    const std::lock_guard lock(mutex_);
    waiting_ = std::move(map);
  }
  changed_.notify_all();
}

void BackgroundMapWriter::wait_until_written() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !waiting_ && !writing_; });
}

bool BackgroundMapWriter::last_write_failed() {
  const std::lock_guard lock(mutex_);
  return last_write_failed_;
}

void BackgroundMapWriter::run() {
  // A thread started after the daemon turned real-time would inherit SCHED_FIFO: a file write
  // must not compete with the frame loop.
  const sched_param normal{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return waiting_ || stop_; });
    if (!waiting_) return;  // stopped, nothing left to write
    const MarkerMap map = std::move(*waiting_);
    waiting_.reset();
    writing_ = true;
    lock.unlock();
    write(map);
    lock.lock();
    writing_ = false;
    changed_.notify_all();
  }
}

void BackgroundMapWriter::write(const MarkerMap& map) {
  std::optional<std::string> error;
  try {
    write_map_(output_, map);
  } catch (const io::InputError& e) {
    error = e.what();
  }
  const std::lock_guard lock(mutex_);
  if (error && !last_write_failed_) {
    std::fprintf(log_, "%s%s: the previous map stays; trying again at the next write\n", log_prefix_.c_str(),
                 error->c_str());
  }
  if (!error && last_write_failed_) std::fprintf(log_, "%s%s: written again\n", log_prefix_.c_str(), output_.c_str());
  last_write_failed_ = error.has_value();
}

}  // namespace irloc::firmware
