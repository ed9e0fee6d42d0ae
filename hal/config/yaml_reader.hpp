#pragma once
// Strict YAML reading: every value checked, every unknown key an error naming file, line and key.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace irloc::hal {

// Parses a YAML file; throws InputError naming the file when it is missing or malformed.
YAML::Node load_yaml_file(const std::filesystem::path& path);

// A YAML mapping read field by field. Each accessor records the key it read, and
// reject_unknown_keys() then names the first key nobody asked for: a typo is never ignored.
// Every problem throws InputError as "FILE:LINE: FIELD: PROBLEM", FIELD the dotted path.
class YamlMap {
 public:
  YamlMap(YAML::Node node, std::string file, std::string field_path);

  bool has(const std::string& key) const;
  double number(const std::string& key);
  std::optional<double> optional_number(const std::string& key);
  long long integer(const std::string& key);
  std::string text(const std::string& key);
  // A sequence of exactly `count` numbers.
  std::vector<double> numbers(const std::string& key, std::size_t count);
  YamlMap map(const std::string& key);
  // The items of a sequence (an absent key is an empty list).
  std::vector<YAML::Node> items(const std::string& key);
  // Accepts a key without reading it (keys a format allows but irloc has no use for).
  void ignore(const std::string& key);

  void reject_unknown_keys() const;

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

  YAML::Node node_;
  std::string file_;
  std::string field_path_;
  std::vector<std::string> read_keys_;
};

// Reads a node as a number or throws through `owner`.
double as_number(const YamlMap& owner, const YAML::Node& node, const std::string& field);

}  // namespace irloc::hal
