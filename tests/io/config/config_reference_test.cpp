// The reference config (irlocd --print-config) against the reader and docs/config.md: every key it
// shows is read, every key read is shown, it reads back to the defaults, docs/config.md is it; and
// every section's table reads back what it writes.
#include <algorithm>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "io/config/config_file.hpp"
#include "io/config/config_reference.hpp"
#include "io/config/dot_config_file.hpp"
#include "io/config/led_config_file.hpp"
#include "io/config/mount_watch_config_file.hpp"
#include "io/config/outside_in_config_file.hpp"
#include "io/config/square_config_file.hpp"
#include "tests/support/temp_dir.hpp"

namespace irloc::io {
namespace {

// The camera of docs/outside_in.md's example floor_reference: 640 x 480, f 500, no distortion.
constexpr const char* kCalibration = R"(image_width: 640
image_height: 480
camera_matrix: {rows: 3, cols: 3, data: [500, 0, 319.5, 0, 500, 239.5, 0, 0, 1]}
distortion_model: plumb_bob
distortion_coefficients: {rows: 1, cols: 5, data: [0, 0, 0, 0, 0]}
)";

constexpr const char* kMap = R"(dot_markers:
  - {id: 1782, origin: [1, 2, 2.6], yaw: 0.3}
)";

// The reference with every key commented out as "# key: value" given: both modes' keys at once.
std::string every_key_given(const std::string& reference) {
  return std::regex_replace(reference, std::regex(R"(^( *)# (\w+:))", std::regex::multiline), "$1$2");
}

// Every key of a YAML document as its dotted field ("camera.mount.xyz").
void collect_keys(const YAML::Node& node, const std::string& prefix, std::set<std::string>& keys) {
  if (!node.IsMap()) return;
  for (const auto& entry : node) {
    const std::string field = prefix.empty() ? entry.first.Scalar() : prefix + "." + entry.first.Scalar();
    keys.insert(field);
    collect_keys(entry.second, field, keys);
  }
}

// The reference with every key given, as mode outside_in reads it: the on-robot sections removed.
YAML::Node outside_in_document(const YAML::Node& every) {
  YAML::Node outside_in = YAML::Clone(every);
  outside_in["mode"] = "outside_in";
  for (const char* key : {"mount", "pixel_bits"}) outside_in["camera"].remove(key);
  for (const char* key : {"front_end", "dot", "square", "led", "mount_watch", "mavlink"}) outside_in.remove(key);
  return outside_in;
}

class ReferenceConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "calib.yaml") << kCalibration;
    std::ofstream(dir_ / "map.yaml") << kMap;
  }
  // Reads `document` as the config file in the test's folder; appends the keys read to `read`.
  RobotConfig read(const YAML::Node& document, std::vector<std::string>* read = nullptr) {
    std::stringstream text;
    text << document;
    const std::string file = (dir_ / "config.yaml").string();
    YamlMap root(parse_yaml_text(text.str(), file), file, "");
    root.log_accepted_keys(read);
    return read_robot_config(root);
  }

  test::TempDir dir_;
};

TEST_F(ReferenceConfig, ReadsBackToTheDefaults) {
  const RobotConfig config = read(YAML::Load(reference_config_yaml()));
  const LocalizerSetup defaults;
  EXPECT_EQ(config.mode, RobotMode::on_robot);
  EXPECT_EQ(config.setup.dof, Dof::planar3);
  EXPECT_EQ(config.setup.line_time_ns, 0);
  // Every value, by its text (the shortest that reads back exactly).
  for (const auto& setting : dot_settings()) {
    EXPECT_EQ(setting_value_text(setting, config.setup.dot), setting_value_text(setting, defaults.dot)) << setting.key;
  }
  for (const auto& setting : front_end_settings()) {
    EXPECT_EQ(setting_value_text(setting, config.setup.dot), setting_value_text(setting, defaults.dot)) << setting.key;
  }
  EXPECT_EQ(config.setup.dot.pixel_bits, defaults.dot.pixel_bits);
  EXPECT_EQ(config.setup.dot.grey_levels.clutter.mean, defaults.dot.grey_levels.clutter.mean);
  for (const auto& setting : square_settings()) {
    EXPECT_EQ(setting_value_text(setting, config.setup.square), setting_value_text(setting, defaults.square)) << setting.key;
  }
  for (const auto& setting : led_settings()) {
    EXPECT_EQ(setting_value_text(setting, config.setup.led), setting_value_text(setting, defaults.led)) << setting.key;
  }
  const calibration::MountWatchConfig watch_defaults;
  for (const auto& setting : mount_watch_settings()) {
    EXPECT_EQ(setting_value_text(setting, config.mount_watch), setting_value_text(setting, watch_defaults)) << setting.key;
  }
  // outside_in's section, commented out for the on-robot mode, reads back to its defaults too.
  const RobotConfig outside = read(outside_in_document(YAML::Load(every_key_given(reference_config_yaml()))));
  ASSERT_TRUE(outside.setup.outside_in);
  const outside_in::OutsideInConfig outside_defaults;
  for (const auto& setting : outside_in_settings()) {
    EXPECT_EQ(setting_value_text(setting, *outside.setup.outside_in), setting_value_text(setting, outside_defaults))
        << setting.key;
  }
}

TEST_F(ReferenceConfig, ShowsEveryKeyTheReaderReadsAndNoOther) {
  const YAML::Node every = YAML::Load(every_key_given(reference_config_yaml()));
  std::set<std::string> shown;
  collect_keys(every, "", shown);

  std::vector<std::string> read_keys;
  // on_robot, its mount by preset and rpy, then by rotation.
  YAML::Node on_robot = YAML::Clone(every);
  on_robot["camera"].remove("floor_reference");
  on_robot["robot"].remove("body");
  on_robot.remove("outside_in");
  YAML::Node by_rotation = YAML::Clone(on_robot);
  on_robot["camera"]["mount"].remove("rotation");
  read(on_robot, &read_keys);
  by_rotation["camera"]["mount"].remove("preset");
  by_rotation["camera"]["mount"].remove("rpy");
  read(by_rotation, &read_keys);
  // outside_in: the fixed camera of docs/outside_in.md.
  YAML::Node outside_in = outside_in_document(every);
  outside_in["outside_in"]["track_gate_m"] = 0.5;
  outside_in["camera"]["line_time_ns"] = 60000;  // a wall camera's rolling shutter (docs/outside_in.md)
  const RobotConfig outside = read(outside_in, &read_keys);
  EXPECT_EQ(outside.mode, RobotMode::outside_in);
  EXPECT_EQ(outside.setup.line_time_ns, 60000);
  ASSERT_TRUE(outside.setup.outside_in);
  EXPECT_EQ(outside.setup.outside_in->track_gate_m, 0.5);

  // The keys that moved out of dot: are read there too, under their old names (docs/formats.md).
  std::set<std::string> old_names;
  for (const auto& setting : camera_pixel_settings()) old_names.insert(std::string("dot.") + setting.key);
  for (const auto& setting : front_end_settings()) old_names.insert(std::string("dot.") + setting.key);

  const std::set<std::string> read_set(read_keys.begin(), read_keys.end());
  for (const std::string& key : shown) EXPECT_TRUE(read_set.count(key)) << key << ": shown but not read";
  for (const std::string& key : read_set) {
    EXPECT_TRUE(shown.count(key) || old_names.count(key)) << key << ": read but not shown";
  }
}

TEST_F(ReferenceConfig, IsTheDocsPage) {
  std::ifstream page(IRLOC_DOCS_DIR "/config.md");
  ASSERT_TRUE(page) << IRLOC_DOCS_DIR "/config.md";
  std::string line, block;
  bool inside = false;
  while (std::getline(page, line)) {
    if (!inside && line == "```yaml") {
      inside = true;
    } else if (inside && line == "```") {
      break;
    } else if (inside) {
      block += line + "\n";
    }
  }
  EXPECT_EQ(block, reference_config_yaml())
      << "docs/config.md's config is not irlocd --print-config's: paste the output between its ```yaml fences";
}

// Every member set away from its default, written as "key: value" lines, reads back the same.
template <typename Section>
void expect_round_trip(std::span<const Setting<Section>> table) {
  static const Section defaults;
  static Section changed;
  std::set<std::string> keys;
  std::string text;
  for (const Setting<Section>& setting : table) {
    EXPECT_TRUE(keys.insert(setting.key).second) << setting.key << ": declared twice";
    for (const Setting<Section>& other : table) {
      if (&other != &setting) {
        EXPECT_NE(other.member, setting.member) << setting.key << " and " << other.key << ": one member";
      }
    }
    std::visit(
        [&](auto member) {
          auto& value = changed.*member;
          using Value = std::remove_reference_t<decltype(value)>;
          if constexpr (std::is_same_v<Value, bool>) {
            value = !(defaults.*member);
          } else {
            value = static_cast<Value>(defaults.*member == static_cast<Value>(setting.high) ? setting.low : setting.high);
          }
        },
        setting.member);
    text += std::string(setting.key) + ": " + setting_value_text(setting, changed) + "\n";
  }
  YamlMap section(parse_yaml_text(text, "section.yaml"), "section.yaml", "");
  static Section read_back;
  read_settings(section, table, read_back);
  section.reject_unknown_keys();
  for (const Setting<Section>& setting : table) {
    EXPECT_EQ(setting_value_text(setting, read_back), setting_value_text(setting, changed)) << setting.key;
    EXPECT_NE(setting_value_text(setting, read_back), setting_value_text(setting, defaults)) << setting.key;
  }
}

TEST(SettingTables, ReadBackWhatTheyWrite) {
  expect_round_trip(dot_settings());
  expect_round_trip(grey_level_settings());
  expect_round_trip(front_end_settings());
  expect_round_trip(camera_pixel_settings());
  expect_round_trip(square_settings());
  expect_round_trip(led_settings());
  expect_round_trip(mount_watch_settings());
  expect_round_trip(outside_in_settings());
}

}  // namespace
}  // namespace irloc::io
