#pragma once
// Writes a frame dataset (docs/formats.md): frames.csv and one PGM per frame. Used by the
// simulator's renderer, by recording on the robot, and by tests.

#include <cstdint>
#include <filesystem>
#include <fstream>

#include "algo/frames/frame.hpp"

namespace irloc::hal {

class DatasetWriter {
 public:
  // Creates DIR (and parents) and DIR/frames.csv; throws InputError when it cannot.
  // 16-bit frames are written with `maxval16` (1023 for 10-bit, 4095 for 12-bit sensors).
  explicit DatasetWriter(const std::filesystem::path& dir, int maxval16 = 65535);

  // Writes DIR/frame_<seq>.pgm and its frames.csv row.
  void write(const Frame& frame);

  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
  std::ofstream index_;
  int maxval16_;
};

}  // namespace irloc::hal
