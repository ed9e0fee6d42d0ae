#pragma once
// A dataset's frames.csv (docs/formats.md): one row per frame, its sequence number, capture time,
// LED state and PGM file; written by DatasetWriter, read by the `dir:` camera.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace irloc::io {

inline constexpr std::string_view kFramesCsvHeader = "seq,t_ns,led,file";

struct FrameIndexRow {
  std::uint64_t seq;
  std::int64_t t_ns;
  bool led_on;
  std::string path;  // the file field joined to the dataset's folder
};

// Reads and checks DIR/frames.csv: a regular file of bounded size (256 MiB); the header, four
// fields a row, strictly increasing seq and t_ns, every frame a regular file; at least one row.
// Throws InputError naming the file and line.
std::vector<FrameIndexRow> read_frames_index(const std::filesystem::path& dir);

}  // namespace irloc::io
