#pragma once
// Writes pose attempts as the pose CSV of docs/formats.md.

#include <cstdio>
#include <filesystem>
#include <string>

#include "algo/pipeline/pose_estimate.hpp"

namespace irloc::hal {

// Rows are flushed as they are written, so that whatever was computed before a later error or
// a crash stays in the file. Allocates nothing per row.
class PoseCsvWriter {
 public:
  static constexpr const char* kHeader = "seq,t_ns,status,x,y,z,roll,pitch,yaw,marker_id,confidence,source";

  // Creates or truncates the file and writes the header; throws InputError when it cannot.
  explicit PoseCsvWriter(const std::filesystem::path& path);
  ~PoseCsvWriter();
  PoseCsvWriter(const PoseCsvWriter&) = delete;
  PoseCsvWriter& operator=(const PoseCsvWriter&) = delete;

  // ok rows: metres and radians to 1e-6, confidence to 1e-4. none rows: empty pose fields,
  // marker_id -1, confidence 0. Throws InputError when the write fails (disk full).
  void write(const PoseEstimate& estimate);

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  char buffer_[4096];
};

}  // namespace irloc::hal
