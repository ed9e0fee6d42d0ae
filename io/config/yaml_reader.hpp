#pragma once
// Strict YAML reading: every value checked against its range, every unknown or repeated key an
// error naming file, line and key.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "algo/geometry/pose.hpp"

namespace irloc::io {

// The largest YAML file irloc reads (a map of tens of thousands of markers fits).
inline constexpr std::size_t kMaxYamlBytes = 16 << 20;

// Parses a YAML file (a regular file of at most kMaxYamlBytes, opened without blocking); throws
// InputError naming the file when it is missing, special, too large or malformed, when a mapping
// repeats a key, or when a key is not a plain scalar.
YAML::Node load_yaml_file(const std::filesystem::path& path);
// The same for YAML text already in memory; `name` stands for the file in messages.
YAML::Node parse_yaml_text(const std::string& text, const std::string& name);

// A closed range [low, high] for a value read from a file.
struct Range {
  double low;
  double high;
};

// A YAML mapping read field by field. Each accessor records the key it read, and
// reject_unknown_keys() then names the first key nobody asked for: a typo is never ignored.
// Every problem throws InputError as "FILE:LINE: FIELD: PROBLEM", FIELD the dotted path; a value
// out of its range as "FILE:LINE: FIELD: must be in [LOW, HIGH], got VALUE".
class YamlMap {
 public:
  // `file` is the file the node came from; relative paths it names are resolved against its folder.
  YamlMap(YAML::Node node, std::string file, std::string field_path);

  bool has(const std::string& key) const;

  // Required values.
  double number(const std::string& key, Range range);
  long long integer(const std::string& key, long long low, long long high);
  std::string text(const std::string& key);
  bool boolean(const std::string& key);
  // A path relative to this file's folder, or absolute.
  std::filesystem::path path(const std::string& key);
  // robot.dof: 3, 4 or 6.
  Dof dof(const std::string& key);
  // A list of exactly `count` numbers, each in `range`.
  std::vector<double> numbers(const std::string& key, std::size_t count, Range range);
  Eigen::Vector2d vector2(const std::string& key, Range range);
  Eigen::Vector3d vector3(const std::string& key, Range range);
  YamlMap map(const std::string& key);

  // Optional values: the fallback (or nothing) when the key is absent.
  double number(const std::string& key, Range range, double fallback);
  std::optional<double> optional_number(const std::string& key, Range range);
  long long integer(const std::string& key, long long low, long long high, long long fallback);
  bool boolean(const std::string& key, bool fallback);
  std::optional<YamlMap> optional_map(const std::string& key);

  // The items of a sequence (an absent key is an empty list).
  std::vector<YAML::Node> items(const std::string& key);
  // Calls read(item) for every mapping in the list `key` (FIELD "key[i]"), then rejects the
  // item's unknown keys.
  template <typename Read>
  void for_each_item(const std::string& key, Read read) {
    const std::vector<YAML::Node> nodes = items(key);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      YamlMap item(nodes[i], file_, field(key) + "[" + std::to_string(i) + "]");
      item.accepted_log_ = accepted_log_;
      read(item);
      item.reject_unknown_keys();
    }
  }
  // A list of points, each a list of `dimensions` numbers in `range`.
  std::vector<std::vector<double>> points(const std::string& key, std::size_t dimensions, Range range);
  // A list of integers, each in [low, high].
  std::vector<long long> integers(const std::string& key, long long low, long long high);

  // Accepts a key without reading it (keys a format allows but irloc has no use for).
  void ignore(const std::string& key);

  void reject_unknown_keys() const;

  // From now on every key this map or a map read from it accepts is appended to `log` as its
  // dotted field (the test that the documented keys are the keys read compares them).
  void log_accepted_keys(std::vector<std::string>* log) { accepted_log_ = log; }

  // Throws "FILE:LINE: FIELD: PROBLEM" for a value read from this map (node may be this map's).
  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& problem) const;
  [[noreturn]] void fail(const std::string& problem) const;
  // Throws for the value of `key`, pointing at its line.
  [[noreturn]] void fail_key(const std::string& key, const std::string& problem) const;

  const std::string& file() const { return file_; }
  const std::string& field_path() const { return field_path_; }
  std::string field(const std::string& key) const;

 private:
  YAML::Node value(const std::string& key);
  void accept(const std::string& key);
  double number_at(const YAML::Node& node, const std::string& key, Range range) const;
  long long integer_at(const YAML::Node& node, const std::string& key, long long low, long long high) const;

  YAML::Node node_;
  std::string file_;
  std::string field_path_;
  std::vector<std::string> read_keys_;
  std::vector<std::string>* accepted_log_ = nullptr;
};

// "[LOW, HIGH]" as the range messages print it (shortest round-trip numbers).
std::string range_text(double low, double high);
// A number as messages print it: the shortest text that reads back to the same value.
std::string number_text(double value);

}  // namespace irloc::io
