// The --serial argument: none, PATH, PATH:BAUD, and paths that contain colons themselves.

#include <gtest/gtest.h>

#include "firmware/serial_spec.hpp"
#include "hal/input_error.hpp"

namespace irloc::firmware {
namespace {

TEST(SerialSpec, NoneIsNoPort) { EXPECT_FALSE(parse_serial_spec("none").has_value()); }

TEST(SerialSpec, PathAloneTakesTheDefaultBaud) {
  const auto spec = parse_serial_spec("/dev/ttyAMA0");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->path, "/dev/ttyAMA0");
  EXPECT_EQ(spec->baud, 115200);
}

TEST(SerialSpec, TrailingDigitsAreTheBaud) {
  const auto spec = parse_serial_spec("/dev/ttyUSB0:921600");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->path, "/dev/ttyUSB0");
  EXPECT_EQ(spec->baud, 921600);
}

TEST(SerialSpec, ColonsInsideAPathStayInThePath) {
  const std::string by_path = "/dev/serial/by-path/pci-0000:00:14.0-usb-0:1:1.0-port0";
  const auto spec = parse_serial_spec(by_path);
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->path, by_path);
  const auto with_baud = parse_serial_spec(by_path + ":57600");
  ASSERT_TRUE(with_baud);
  EXPECT_EQ(with_baud->path, by_path);
  EXPECT_EQ(with_baud->baud, 57600);
}

TEST(SerialSpec, BadBaudAndEmptyPathAreErrors) {
  EXPECT_THROW(parse_serial_spec("/dev/ttyUSB0:12345"), hal::InputError);
  EXPECT_THROW(parse_serial_spec("/dev/ttyUSB0:99999999999999"), hal::InputError);
  EXPECT_THROW(parse_serial_spec(":115200"), hal::InputError);
}

}  // namespace
}  // namespace irloc::firmware
