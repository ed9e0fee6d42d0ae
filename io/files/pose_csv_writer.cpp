#include "io/files/pose_csv_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>

#include "io/files/output_file.hpp"
#include "io/input_error.hpp"

namespace irloc::io {
namespace {

// Appends to a fixed line buffer; locale-independent and allocation-free.
class LineBuilder {
 public:
  void text(std::string_view s) {
    for (char c : s) put(c);
  }
  void integer(long long value) { advance(std::to_chars(cursor_, end_, value)); }
  void unsigned_integer(std::uint64_t value) { advance(std::to_chars(cursor_, end_, value)); }
  void fixed(double value, int decimals) {
    advance(std::to_chars(cursor_, end_, value, std::chars_format::fixed, decimals));
  }
  void put(char c) {
    if (cursor_ < end_) *cursor_++ = c;
  }
  std::string_view line() const { return {line_, static_cast<std::size_t>(cursor_ - line_)}; }

 private:
  void advance(std::to_chars_result result) {
    if (result.ec == std::errc()) cursor_ = result.ptr;
  }
  char line_[256];
  char* cursor_ = line_;
  char* const end_ = line_ + sizeof line_;
};

}  // namespace

PoseCsvWriter::PoseCsvWriter(const std::filesystem::path& path) : path_(path.string()) {
  struct stat existing {};
  if (::stat(path_.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode)) {
    throw InputError(path_ + ": is no regular file: refusing to write the pose CSV to it");
  }
  // O_NONBLOCK: a FIFO in its place must not block; it is refused below, as is anything else
  // that is no regular file. O_NOFOLLOW: never written through a link. Truncated only then.
  fd_ = UniqueFd(::open(path_.c_str(), O_WRONLY | O_CREAT | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY, 0644));
  if (fd_.get() < 0) throw InputError(path_ + ": cannot write: " + std::strerror(errno));
  struct stat status {};
  if (::fstat(fd_.get(), &status) != 0 || !S_ISREG(status.st_mode)) {
    throw InputError(path_ + ": is no regular file: refusing to write the pose CSV to it");
  }
  if (::ftruncate(fd_.get(), 0) != 0) throw InputError(path_ + ": cannot write: " + std::strerror(errno));
  const std::string header = std::string(kHeader) + "\n";
  write_all(fd_.get(), header.data(), header.size(), path_);
  whole_rows_end_ = header.size();
}

void PoseCsvWriter::write(const PoseEstimate& estimate) {
  LineBuilder row;
  row.unsigned_integer(estimate.seq);
  row.put(',');
  row.integer(estimate.t_ns);
  row.put(',');
  if (estimate.ok) {
    row.text("ok");
    for (double value : {estimate.x, estimate.y, estimate.z, estimate.roll, estimate.pitch, estimate.yaw}) {
      row.put(',');
      row.fixed(value, 6);
    }
    row.put(',');
    row.integer(estimate.marker_id);
    row.put(',');
    row.fixed(estimate.confidence, 4);
  } else {
    row.text("none,,,,,,,-1,0");
  }
  row.put(',');
  row.text(to_string(estimate.source));
  row.put('\n');
  const std::string_view line = row.line();
  // One write() per row; a short one (the disk filling) is retried for the rest, which then
  // fails with the reason. The partial row is cut off: the file ends with the last whole row.
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t written = ::write(fd_.get(), line.data() + done, line.size() - done);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      const int error = written < 0 ? errno : ENOSPC;
      if (::ftruncate(fd_.get(), static_cast<off_t>(whole_rows_end_)) != 0 ||
          ::lseek(fd_.get(), static_cast<off_t>(whole_rows_end_), SEEK_SET) < 0) {
        throw InputError(path_ + ": cannot write: " + std::strerror(error) + ", and cannot cut the partial row off: " +
                         std::strerror(errno));
      }
      throw InputError(path_ + ": cannot write: " + std::strerror(error));
    }
    done += static_cast<std::size_t>(written);
  }
  whole_rows_end_ += line.size();
  ++rows_written_;
}

}  // namespace irloc::io
