// The one YAML reader every file goes through: ranges in one message style, repeated and complex
// keys, and files that are not regular files.
#include "io/config/yaml_reader.hpp"

#include <sys/stat.h>

#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/config/board_file.hpp"
#include "io/config/calibration_file.hpp"
#include "io/config/config_file.hpp"
#include "io/config/map_file.hpp"
#include "io/input_error.hpp"
#include "tests/support/input_error_message.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

using ::testing::HasSubstr;

class YamlReader : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  std::string load_error(const std::string& text) {
    const std::filesystem::path file = write("file.yaml", text);
    return test::input_error_message([&] { load_yaml_file(file); });
  }
  std::string file() const { return (dir_ / "file.yaml").string(); }

  test::TempDir dir_;
};

TEST_F(YamlReader, OutOfRangeValuesNameFileLineKeyRangeAndValue) {
  const std::filesystem::path path = write("file.yaml", "a:\n  gain: 1e308\n  count: 70\n  flag: yes\n");
  YamlMap root(load_yaml_file(path), path.string(), "");
  YamlMap a = root.map("a");
  EXPECT_EQ(test::input_error_message([&] { a.number("gain", {1, 64}); }),
            file() + ":2: a.gain: must be in [1, 64], got 1e+308");
  EXPECT_EQ(test::input_error_message([&] { a.integer("count", 1, 64); }), file() + ":3: a.count: must be in [1, 64], got 70");
  EXPECT_EQ(test::input_error_message([&] { a.number("gain", {1, 64}, 2); }),
            file() + ":2: a.gain: must be in [1, 64], got 1e+308");
  EXPECT_EQ(test::input_error_message([&] { a.boolean("flag"); }), file() + ":4: a.flag: expected true or false, got 'yes'");
  EXPECT_DOUBLE_EQ(a.number("absent", {1, 64}, 2), 2);
  EXPECT_EQ(a.integer("absent_count", 1, 64, 7), 7);
}

TEST_F(YamlReader, RelativePathsAreRelativeToTheFile) {
  const std::filesystem::path path = write("file.yaml", "a: sub/x.yaml\nb: /abs/y.yaml\nc: ''\n");
  YamlMap root(load_yaml_file(path), path.string(), "");
  EXPECT_EQ(root.path("a"), dir_.path() / "sub/x.yaml");
  EXPECT_EQ(root.path("b"), std::filesystem::path("/abs/y.yaml"));
  EXPECT_EQ(test::input_error_message([&] { root.path("c"); }), file() + ":3: c: expected a file name, got an empty one");
}

TEST_F(YamlReader, DuplicateKeyNamesBothLines) {
  EXPECT_EQ(load_error("robot:\n  dof: 6\n  dof: 3\n"), file() + ":3: dof: duplicate key (first given on line 2)");
  EXPECT_EQ(load_error("a: 1\nb: [{x: 1, x: 2}]\n"), file() + ":2: x: duplicate key (first given on line 2)");
}

TEST_F(YamlReader, ComplexKeyIsOneClearMessage) {
  EXPECT_EQ(load_error("? [a, b]\n: 1\n"), file() + ":1: a key must be a plain name, not a list or mapping (complex key '?')");
  EXPECT_EQ(load_error("robot:\n  ? {dof: 3}\n  : 1\n"),
            file() + ":2: a key must be a plain name, not a list or mapping (complex key '?')");
}

TEST_F(YamlReader, AliasesCannotMakeTheWalkUnbounded) {
  // Nine levels of ten aliases each: 10^9 nodes if every use were walked.
  std::string text = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (char level = '1'; level <= '9'; ++level) {
    text += {'l', level, ':', ' ', '&', 'l', level, ' ', '['};
    for (int k = 0; k < 10; ++k) text += {'*', 'l', static_cast<char>(level - 1), k < 9 ? ',' : ']', k < 9 ? ' ' : '\n'};
  }
  EXPECT_THAT(load_error(text), HasSubstr(file() + ": too many YAML nodes"));
}

TEST_F(YamlReader, SpecialFilesAreRefusedWithoutBlocking) {
  const std::filesystem::path fifo = dir_ / "fifo.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(test::input_error_message([&] { load_yaml_file(fifo); }),
            fifo.string() + ": is a special file (FIFO, device or socket), expected a regular file");
  const std::filesystem::path zero = dir_ / "zero.yaml";
  std::filesystem::create_symlink("/dev/zero", zero);
  EXPECT_EQ(test::input_error_message([&] { load_yaml_file(zero); }),
            zero.string() + ": is a special file (FIFO, device or socket), expected a regular file");
  std::filesystem::create_directory(dir_ / "folder.yaml");
  EXPECT_EQ(test::input_error_message([&] { load_yaml_file(dir_ / "folder.yaml"); }),
            (dir_ / "folder.yaml").string() + ": is a directory, expected a regular file");
  const std::filesystem::path large = dir_ / "large.yaml";
  std::filesystem::resize_file(write("large.yaml", "a: 1\n"), kMaxYamlBytes + 1);
  EXPECT_THAT(test::input_error_message([&] { load_yaml_file(large); }), HasSubstr(large.string() + ": too large"));
}

// Every file kind refuses a repeated key (yaml-cpp alone would keep the first value silently).
TEST_F(YamlReader, EveryFileKindRefusesDuplicateKeys) {
  const std::string calibration =
      "image_width: 64\nimage_height: 48\ncamera_matrix: {rows: 3, cols: 3, data: [50, 0, 32, 0, 50, 24, 0, 0, 1]}\n"
      "distortion_model: plumb_bob\ndistortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}\n";
  write("calib.yaml", calibration + "image_width: 32\n");
  EXPECT_EQ(test::input_error_message([&] { load_camera_info(dir_ / "calib.yaml"); }),
            (dir_ / "calib.yaml").string() + ":6: image_width: duplicate key (first given on line 1)");
  write("map.yaml", "dot_markers:\n  - {id: 1, origin: [0, 0, 2], yaw: 0, yaw: 1}\n");
  EXPECT_EQ(test::input_error_message([&] { load_marker_map(dir_ / "map.yaml"); }),
            (dir_ / "map.yaml").string() + ":2: yaw: duplicate key (first given on line 2)");
  write("board.yaml", "name: a\nname: b\n");
  EXPECT_EQ(test::input_error_message([&] { load_board(dir_ / "board.yaml"); }),
            (dir_ / "board.yaml").string() + ":2: name: duplicate key (first given on line 1)");
  write("calib.yaml", calibration);
  write("map.yaml", "dot_markers:\n  - {id: 1, origin: [0, 0, 2], yaw: 0}\n");
  write("config.yaml", "camera:\n  calibration: calib.yaml\n  mount: {preset: up, xyz: [0, 0, 0]}\nrobot:\n  dof: 6\n"
                       "  dof: 3\nmap: map.yaml\n");
  EXPECT_EQ(test::input_error_message([&] { load_robot_config(dir_ / "config.yaml"); }),
            (dir_ / "config.yaml").string() + ":6: dof: duplicate key (first given on line 5)");
}

}  // namespace
}  // namespace irloc::io
