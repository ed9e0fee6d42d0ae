#pragma once
// A binary image packed 64 pixels to a word, with a flag per row saying whether any pixel of it
// is set, so that the binary kernels and their readers skip empty rows (most of a sparse IR mask).
//
// Pixel x of row y is bit x % 64 (least significant first) of word x / 64 of the row; the bits
// of the last word beyond the width are always 0.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace irloc {

class BitImage {
 public:
  BitImage() = default;
  // Allocated here, at start-up; every image is cleared.
  BitImage(int width, int height)
      : width_(width),
        height_(height),
        words_per_row_((width + 63) / 64),
        words_(static_cast<std::size_t>(words_per_row_) * static_cast<std::size_t>(height)),
        row_set_(static_cast<std::size_t>(height), 0) {}

  int width() const { return width_; }
  int height() const { return height_; }
  int words_per_row() const { return words_per_row_; }

  std::uint64_t* row(int y) { return words_.data() + static_cast<std::size_t>(y) * words_per_row_; }
  const std::uint64_t* row(int y) const { return words_.data() + static_cast<std::size_t>(y) * words_per_row_; }
  bool get(int x, int y) const { return (row(y)[x / 64] >> (x % 64)) & 1u; }

  // Whether row y has a set pixel. A row whose flag is false is all zero: whoever writes a row
  // sets its flag (set_row_flag) or clears it (clear_row).
  bool row_set(int y) const { return row_set_[static_cast<std::size_t>(y)] != 0; }
  void set_row_flag(int y, bool set) { row_set_[static_cast<std::size_t>(y)] = set ? 1 : 0; }
  // Sets pixels [x_begin, x_end) of row y (0 <= x_begin < x_end <= width) and the row's flag.
  void set_range(int y, int x_begin, int x_end) {
    std::uint64_t* words = row(y);
    const int first = x_begin / 64, last = (x_end - 1) / 64;
    const std::uint64_t from_begin = ~std::uint64_t{0} << (x_begin % 64);
    const std::uint64_t to_end = ~std::uint64_t{0} >> (63 - (x_end - 1) % 64);
    if (first == last) {
      words[first] |= from_begin & to_end;
    } else {
      words[first] |= from_begin;
      std::fill(words + first + 1, words + last, ~std::uint64_t{0});
      words[last] |= to_end;
    }
    set_row_flag(y, true);
  }
  void clear_row(int y) {
    if (!row_set(y)) return;  // already zero
    std::fill_n(row(y), words_per_row_, std::uint64_t{0});
    set_row_flag(y, false);
  }

 private:
  int width_ = 0;
  int height_ = 0;
  int words_per_row_ = 0;
  std::vector<std::uint64_t> words_;
  std::vector<std::uint8_t> row_set_;
};

}  // namespace irloc
