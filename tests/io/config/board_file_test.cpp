// Board files: the shipped boards parse and name what a robot needs; mistakes are one line
// naming file, line and field.

#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/config/board_file.hpp"
#include "io/config/calibration_file.hpp"
#include "io/input_error.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

const std::filesystem::path kBoards = IRLOC_BOARDS_DIR;

TEST(BoardFile, ShippedBoardsParseAndNameCameraLensStrobeAndSerial) {
  for (const char* name : {"rpi4-noir", "rpi5-gs-mono", "x86-uvc"}) {
    const BoardConfig board = load_board(kBoards / (std::string(name) + ".yaml"));
    EXPECT_EQ(board.name, name);
    EXPECT_FALSE(board.camera.formats.empty());
    EXPECT_GE(board.camera.frame_duration_us, board.camera.exposure_us);
    ASSERT_TRUE(board.strobe.has_value()) << name;
    EXPECT_FALSE(board.strobe->chip.empty());
    ASSERT_TRUE(board.serial.has_value()) << name;
    EXPECT_TRUE(board.serial->device.starts_with("/dev/"));
    const CameraIntrinsics lens = load_camera_info(board.camera.calibration);  // the lens file exists and parses
    EXPECT_GT(lens.width, 0);
  }
  EXPECT_EQ(load_board(kBoards / "rpi5-gs-mono.yaml").camera.formats.front(), "R8");
  EXPECT_EQ(load_board(kBoards / "x86-uvc.yaml").serial->protocol, "stargazer");
  // The IMX219's rolling shutter at 820x616: the rows take 23 ms; the IMX296 is a global shutter.
  EXPECT_EQ(load_board(kBoards / "rpi4-noir.yaml").camera.line_time_ns, 37800);
  EXPECT_EQ(load_board(kBoards / "rpi5-gs-mono.yaml").camera.line_time_ns, 0);
}

std::string error_for(const std::string& edit_from, const std::string& edit_to) {
  test::TempDir dir;
  std::ifstream in(kBoards / "rpi4-noir.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find(edit_from);
  EXPECT_NE(at, std::string::npos) << edit_from;
  text.replace(at, edit_from.size(), edit_to);
  const std::filesystem::path path = dir / "board.yaml";
  std::ofstream(path) << text;
  try {
    load_board(path);
  } catch (const InputError& e) {
    const std::string message = e.what();
    return message.substr(message.find(':') + 1);  // without the temporary folder's name
  }
  return "(no error)";
}

TEST(BoardFile, MistakesNameLineAndField) {
  EXPECT_EQ(error_for("  line: 17", "  lines: 17"), "17: strobe.line: required but missing");
  EXPECT_EQ(error_for("  baud: 921600", "  baud: 921600\n  parity: none"), "26: serial.parity: unknown key");
  EXPECT_EQ(error_for("protocol: mavlink", "protocol: nmea"), "26: serial.protocol: unknown protocol 'nmea' (expected mavlink or stargazer)");
  EXPECT_EQ(error_for("exposure_us: 1500", "exposure_us: 30000"), "11: camera.exposure_us: longer than frame_duration_us");
  EXPECT_EQ(error_for("active_low: false", "active_low: maybe"), "19: strobe.active_low: expected true or false, got 'maybe'");
  // A rate no serial device can be set to: the board's field, not a --serial the user never gave.
  EXPECT_EQ(error_for("  baud: 921600", "  baud: 12345"),
            "25: serial.baud: unsupported baud rate 12345 (supported: 9600 19200 38400 57600 115200 230400 460800 500000 576000 "
            "921600 1000000 1152000 1500000 2000000 3000000 4000000)");
}

TEST(BoardFile, AbsurdNumbersAreOutOfRange) {
  EXPECT_EQ(error_for("analogue_gain: 4.0", "analogue_gain: 1e308"), "12: camera.analogue_gain: must be in [1, 64], got 1e+308");
  EXPECT_EQ(error_for("position_sigma_m: 0.02", "position_sigma_m: 1e308"),
            "30: mavlink.position_sigma_m: must be in [1e-06, 100], got 1e+308");
  EXPECT_EQ(error_for("angle_sigma_rad: 0.02", "angle_sigma_rad: 0"), "31: mavlink.angle_sigma_rad: must be in [1e-06, 3.2], got 0");
}

}  // namespace
}  // namespace irloc::io
