#pragma once
// Writes a frame dataset (docs/formats.md): frames.csv and one PGM per frame. Used by the
// simulator's renderer, by recording on the robot, and by tests.

#include <cstdint>
#include <filesystem>

#include "algo/frames/frame.hpp"
#include "hal/files/output_file.hpp"

namespace irloc::hal {

class DatasetWriter {
 public:
  // Creates DIR (and parents) and DIR/frames.csv; throws InputError when it cannot, or when DIR
  // already holds files (a dataset is never mixed into another one or written over). Files are
  // created new, never through a symbolic link.
  // 16-bit frames are written with `maxval16` (1023 for 10-bit, 4095 for 12-bit sensors).
  explicit DatasetWriter(const std::filesystem::path& dir, int maxval16 = 65535);

  // Writes DIR/frame_<seq>.pgm and its frames.csv row.
  void write(const Frame& frame);

  const std::filesystem::path& dir() const { return folder_.path(); }

 private:
  NewFilesFolder folder_;
  UniqueFd index_;
  std::string index_name_;
  int maxval16_;
};

}  // namespace irloc::hal
