// io/dataset/pgm: the binary PGM header as the dataset format reads it (docs/formats.md).

#include <string>

#include <gtest/gtest.h>

#include "io/dataset/pgm.hpp"
#include "io/input_error.hpp"

namespace irloc::io {
namespace {

PgmHeader header_of(const std::string& bytes) {
  return parse_pgm_header({reinterpret_cast<const std::byte*>(bytes.data()), bytes.size()}, "x.pgm");
}

std::string header_error(const std::string& bytes) {
  try {
    header_of(bytes);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Pgm, ParsesHeadersWithComments) {
  const PgmHeader header = header_of("P5\n# made by hand\n 640  480\n# depth\n4095\n....");
  EXPECT_EQ(header.width, 640);
  EXPECT_EQ(header.height, 480);
  EXPECT_EQ(header.maxval, 4095);
  EXPECT_EQ(header.bytes_per_pixel(), 2);
  EXPECT_EQ(header.pixel_offset, std::string("P5\n# made by hand\n 640  480\n# depth\n4095\n").size());
  EXPECT_EQ(header_of("P5 3 2 255 ").bytes_per_pixel(), 1);
}

TEST(Pgm, RejectsWhatIsNotABinaryPgm) {
  EXPECT_EQ(header_error("P2\n3 2\n255\n"), "x.pgm: not a valid binary PGM: it does not start with P5");
  EXPECT_EQ(header_error("P5\n3\n"), "x.pgm: not a valid binary PGM: expected the height in the header");
  EXPECT_EQ(header_error("P5\n3 2\n70000\n"), "x.pgm: not a valid binary PGM: maxval must be 1..65535");
  EXPECT_EQ(header_error("P5\n0 2\n255\n"), "x.pgm: not a valid binary PGM: width and height must be at least 1");
  EXPECT_EQ(header_error("P5\n3 2\n255"), "x.pgm: not a valid binary PGM: expected white space after maxval");
}
}  // namespace
}  // namespace irloc::io
