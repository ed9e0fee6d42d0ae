#pragma once
// Writes pose attempts as the pose CSV of docs/formats.md.

#include <cstdint>
#include <filesystem>
#include <string>

#include "algo/pipeline/pose_estimate.hpp"
#include "io/files/input_file.hpp"

namespace irloc::io {

// Each row is one write(), so that whatever was computed before a later error or a crash stays
// in the file, and a row is in the file whole or not at all. Allocates nothing per row.
class PoseCsvWriter {
 public:
  static constexpr const char* kHeader = "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source";

  // Creates or truncates the file and writes the header; throws InputError when it cannot, or when
  // it is no regular file or a symbolic link. What else an output may not be (an input of the
  // run, another output) is io::RunFiles' check, made before this.
  explicit PoseCsvWriter(const std::filesystem::path& path);
  PoseCsvWriter(const PoseCsvWriter&) = delete;
  PoseCsvWriter& operator=(const PoseCsvWriter&) = delete;

  // ok rows: metres and radians to 1e-6, confidence to 1e-4. none rows: empty pose fields,
  // marker_id -1, confidence 0. Throws InputError when the write fails (disk full), after
  // cutting a partly written row off the file.
  void write(const PoseEstimate& estimate);

  const std::string& path() const { return path_; }
  std::uint64_t rows_written() const { return rows_written_; }

 private:
  std::string path_;
  UniqueFd fd_;
  std::uint64_t whole_rows_end_ = 0;  // file size after the last whole row
  std::uint64_t rows_written_ = 0;
};

}  // namespace irloc::io
