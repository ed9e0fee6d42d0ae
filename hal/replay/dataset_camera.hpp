#pragma once
// The `dir:` camera: frames replayed from a recorded or rendered dataset (docs/formats.md).

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hal/camera.hpp"
#include "io/dataset/frames_index.hpp"
#include "io/dataset/pgm.hpp"

namespace irloc::hal {

class DatasetCamera final : public Camera {
 public:
  // Reads DIR/frames.csv (io::read_frames_index), checks that the first frame is
  // width x height, the size the calibration `size_source` gives, and only then sizes the frame
  // buffers. Throws io::InputError naming the file and line.
  DatasetCamera(const std::filesystem::path& dir, int width, int height, const std::string& size_source);

  int width() const override { return width_; }
  int height() const override { return height_; }
  // Reads the next PGM into a ring of three buffers. A frame that is no regular file (opened
  // without blocking), truncated, malformed, of another size than the calibration, of another
  // bit depth than the first frame or with a pixel above its maxval throws io::InputError naming
  // the frame file.
  bool next(Frame& frame) override;
  // The first frame's depth (every later frame must have it).
  bool frames_are_16_bit() const override { return first_depth_bytes_ == 2; }

  // frames.csv and every frame it lists.
  std::vector<std::filesystem::path> input_files() const override;

  std::size_t frame_count() const { return rows_.size(); }

 private:
  struct Slot {
    std::vector<std::byte> file_bytes;
    std::vector<std::uint16_t> pixels16;  // 16-bit frames, converted from big-endian
  };

  void read_file(const io::FrameIndexRow& row, Slot& slot, std::size_t& size) const;
  void check_frame_size(const io::PgmHeader& header, const std::string& path) const;
  void check_first_frame_size();

  std::filesystem::path index_;
  std::vector<io::FrameIndexRow> rows_;
  std::size_t next_row_ = 0;
  int width_ = 0;
  int height_ = 0;
  std::string size_source_;
  int first_depth_bytes_ = 0;  // 1 or 2, the first frame's (its header is read at start)
  std::array<Slot, 3> slots_;
  std::size_t next_slot_ = 0;
};

}  // namespace irloc::hal
