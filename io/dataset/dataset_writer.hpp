#pragma once
// Writes a frame dataset (docs/formats.md): frames.csv and one PGM per frame. Used by the
// simulator's renderer, by recording on the robot, and by tests.

#include <cstdint>
#include <filesystem>

#include "algo/frames/frame.hpp"
#include "io/files/output_file.hpp"

namespace irloc::io {

class DatasetWriter {
 public:
  // Creates DIR (and parents) and DIR/frames.csv; throws InputError when it cannot, or when DIR
  // already holds files (a dataset is never mixed into another one or written over). Files are
  // created new, never through a symbolic link.
  // 16-bit frames are written with `maxval16` (1023 for 10-bit, 4095 for 12-bit sensors).
  explicit DatasetWriter(const std::filesystem::path& dir, int maxval16 = 65535);

  // Writes DIR/frame_<seq>.pgm and its frames.csv row. Throws InputError naming the file when a
  // write fails (the disk filled); the frame's partial PGM is then removed and a partial row cut
  // off, so that DIR stays a valid dataset of the frames written before.
  void write(const Frame& frame);

  const std::filesystem::path& dir() const { return folder_.path(); }
  std::uint64_t frames_written() const { return frames_written_; }

 private:
  NewFilesFolder folder_;
  UniqueFd index_;
  std::string index_name_;
  int maxval16_;
  std::uint64_t index_end_ = 0;  // size of frames.csv after its last whole row
  std::uint64_t frames_written_ = 0;
};

}  // namespace irloc::io
