#include "hal/files/pose_csv_writer.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>

#include "hal/input_error.hpp"

namespace irloc::hal {
namespace {

// Appends to a fixed line buffer; locale-independent and allocation-free.
class LineBuilder {
 public:
  void text(std::string_view s) {
    for (char c : s) put(c);
  }
  void integer(long long value) { advance(std::to_chars(cursor_, end_, value)); }
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
  file_ = std::fopen(path_.c_str(), "w");
  if (file_ == nullptr) throw InputError(path_ + ": cannot write: " + std::strerror(errno));
  std::setvbuf(file_, buffer_, _IOFBF, sizeof buffer_);
  std::fputs(kHeader, file_);
  std::fputc('\n', file_);
  if (std::fflush(file_) != 0) throw InputError(path_ + ": cannot write: " + std::strerror(errno));
}

PoseCsvWriter::~PoseCsvWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void PoseCsvWriter::write(const PoseEstimate& estimate) {
  LineBuilder row;
  row.integer(static_cast<long long>(estimate.seq));
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
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0) {
    throw InputError(path_ + ": cannot write: " + std::strerror(errno));
  }
}

}  // namespace irloc::hal
