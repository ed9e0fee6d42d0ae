#pragma once
// Binary PGM (P5): 8-bit when maxval <= 255, else 16-bit big-endian (docs/formats.md).

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

#include "algo/core/image_view.hpp"

namespace irloc::io {

struct PgmHeader {
  int width = 0;
  int height = 0;
  int maxval = 0;
  std::size_t pixel_offset = 0;  // where the pixel data starts in the file

  int bytes_per_pixel() const { return maxval > 255 ? 2 : 1; }
  std::size_t pixel_bytes() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(bytes_per_pixel());
  }
};

// Parses the header at the start of `file_bytes`; throws InputError "NAME: problem".
PgmHeader parse_pgm_header(std::span<const std::byte> file_bytes, std::string_view name);

// The bytes of a binary PGM file (8-bit: maxval 255; 16-bit: the given maxval, big-endian).
std::string encode_pgm(ImageView8 image);
std::string encode_pgm(ImageView16 image, int maxval);

}  // namespace irloc::io
