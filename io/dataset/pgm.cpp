#include "io/dataset/pgm.hpp"

#include <stdexcept>
#include <string>

#include "io/input_error.hpp"

namespace irloc::io {
namespace {

class HeaderScanner {
 public:
  HeaderScanner(std::span<const std::byte> bytes, std::string_view name) : bytes_(bytes), name_(name) {}

  // Skips white space and '#' comments, then reads a decimal number.
  int number(const char* what) {
    skip_space_and_comments();
    long long value = 0;
    std::size_t digits = 0;
    while (position_ < bytes_.size() && is_digit(peek())) {
      value = value * 10 + (peek() - '0');
      ++position_;
      if (++digits > 6) fail(std::string(what) + " is too large");
    }
    if (digits == 0) fail(std::string("expected the ") + what + " in the header");
    return static_cast<int>(value);
  }
  // Exactly one white-space character ends the header.
  std::size_t end_of_header() {
    if (position_ >= bytes_.size() || !is_space(peek())) fail("expected white space after maxval");
    return position_ + 1;
  }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(std::string(name_) + ": not a valid binary PGM: " + problem);
  }

 private:
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }
  char peek() const { return static_cast<char>(bytes_[position_]); }
  void skip_space_and_comments() {
    while (position_ < bytes_.size()) {
      if (is_space(peek())) {
        ++position_;
      } else if (peek() == '#') {
        while (position_ < bytes_.size() && peek() != '\n') ++position_;
      } else {
        return;
      }
    }
  }

  std::span<const std::byte> bytes_;
  std::string_view name_;
  std::size_t position_ = 2;  // after the magic number
};

std::string header_for(int width, int height, int maxval) {
  return "P5\n" + std::to_string(width) + " " + std::to_string(height) + "\n" + std::to_string(maxval) + "\n";
}

}  // namespace

PgmHeader parse_pgm_header(std::span<const std::byte> file_bytes, std::string_view name) {
  HeaderScanner scanner(file_bytes, name);
  if (file_bytes.size() < 2 || file_bytes[0] != std::byte{'P'} || file_bytes[1] != std::byte{'5'}) {
    scanner.fail("it does not start with P5");
  }
  PgmHeader header;
  header.width = scanner.number("width");
  header.height = scanner.number("height");
  header.maxval = scanner.number("maxval");
  if (header.width < 1 || header.height < 1) scanner.fail("width and height must be at least 1");
  if (header.maxval < 1 || header.maxval > 65535) scanner.fail("maxval must be 1..65535");
  header.pixel_offset = scanner.end_of_header();
  return header;
}

std::string encode_pgm(ImageView8 image) {
  std::string bytes = header_for(image.width(), image.height(), 255);
  bytes.reserve(bytes.size() + static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y) {
    const std::uint8_t* row = image.row(y);
    bytes.append(reinterpret_cast<const char*>(row), static_cast<std::size_t>(image.width()));
  }
  return bytes;
}

std::string encode_pgm(ImageView16 image, int maxval) {
  if (maxval < 256 || maxval > 65535) throw std::invalid_argument("encode_pgm: a 16-bit PGM needs maxval 256..65535");
  std::string bytes = header_for(image.width(), image.height(), maxval);
  bytes.reserve(bytes.size() + 2 * static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()));
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      const std::uint16_t value = image.at(x, y);
      bytes.push_back(static_cast<char>(value >> 8));
      bytes.push_back(static_cast<char>(value & 0xff));
    }
  }
  return bytes;
}

}  // namespace irloc::io
