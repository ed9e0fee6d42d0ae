#include "io/config/yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <utility>

#include "io/files/input_file.hpp"
#include "io/input_error.hpp"

namespace irloc::io {
namespace {

// Walking a document visits an aliased node once per reference: a bound keeps a "billion
// laughs" document from walking forever.
constexpr std::size_t kMaxYamlNodes = 1'000'000;

int line_of(const YAML::Node& node) { return node.Mark().line + 1; }

std::string got_text(const YAML::Node& node) {
  if (!node.IsScalar()) return "a list or mapping";
  return "'" + node.Scalar() + "'";
}

// yaml-cpp keeps the first of two equal keys silently and accepts keys that are lists or
// mappings; both are errors here, for every mapping of the document.
void check_keys(const YAML::Node& node, const std::string& file, std::size_t& visited) {
  if (++visited > kMaxYamlNodes) {
    throw InputError(file + ": too many YAML nodes (more than " + std::to_string(kMaxYamlNodes) +
                     ", aliases counted once per use)");
  }
  if (node.IsSequence()) {
    for (const YAML::Node& item : node) check_keys(item, file, visited);
  } else if (node.IsMap()) {
    std::map<std::string, int> lines;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar()) {
        throw InputError(file + ":" + std::to_string(line_of(entry.first)) +
                         ": a key must be a plain name, not a list or mapping (complex key '?')");
      }
      const std::string& key = entry.first.Scalar();
      const auto [first, inserted] = lines.emplace(key, line_of(entry.first));
      if (!inserted) {
        throw InputError(file + ":" + std::to_string(line_of(entry.first)) + ": " + key +
                         ": duplicate key (first given on line " + std::to_string(first->second) + ")");
      }
      check_keys(entry.second, file, visited);
    }
  }
}

}  // namespace

YAML::Node parse_yaml_text(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(name + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(name + ": malformed YAML: " + e.msg);
  }
  if (!root.IsMap()) throw InputError(name + ": expected a YAML mapping at the top level");
  std::size_t visited = 0;
  check_keys(root, name, visited);
  return root;
}

YAML::Node load_yaml_file(const std::filesystem::path& path) {
  return parse_yaml_text(read_input_file(path, kMaxYamlBytes), path.string());
}

std::string number_text(double value) {
  // The shortest text that reads back exactly, preferring plain decimals unless an exponent
  // is clearly shorter: 100000 and 0.001, but 1e+12, 1e-06 and 1e+308.
  char shortest[32];
  char* shortest_end = std::to_chars(shortest, shortest + sizeof shortest, value).ptr;
  char fixed[400];
  const auto result = std::to_chars(fixed, fixed + sizeof fixed, value, std::chars_format::fixed);
  if (result.ec == std::errc() && result.ptr - fixed <= shortest_end - shortest + 2) return std::string(fixed, static_cast<std::size_t>(result.ptr - fixed));
  return std::string(shortest, static_cast<std::size_t>(shortest_end - shortest));
}

std::string range_text(double low, double high) {
  // Appended, not concatenated: GCC 12 warns falsely (-Wrestrict) on "[" + number_text(low).
  std::string text = "[";
  text += number_text(low);
  text += ", ";
  text += number_text(high);
  text += "]";
  return text;
}

YamlMap::YamlMap(YAML::Node node, std::string file, std::string field_path)
    : node_(std::move(node)), file_(std::move(file)), field_path_(std::move(field_path)) {
  if (!node_.IsMap()) fail(node_, "", "expected a mapping of keys to values");
}

std::string YamlMap::field(const std::string& key) const {
  if (field_path_.empty()) return key;
  if (key.empty()) return field_path_;
  return field_path_ + "." + key;
}

void YamlMap::fail(const YAML::Node& at, const std::string& key, const std::string& problem) const {
  const int line = at.Mark().is_null() ? line_of(node_) : line_of(at);
  const std::string name = field(key);
  throw InputError(file_ + ":" + std::to_string(line) + ": " + (name.empty() ? "" : name + ": ") + problem);
}

void YamlMap::fail(const std::string& problem) const { fail(node_, "", problem); }

void YamlMap::fail_key(const std::string& key, const std::string& problem) const {
  const YAML::Node at = std::as_const(node_)[key];
  fail(at ? at : node_, key, problem);
}

bool YamlMap::has(const std::string& key) const { return static_cast<bool>(std::as_const(node_)[key]); }

YAML::Node YamlMap::value(const std::string& key) {
  accept(key);
  YAML::Node found = std::as_const(node_)[key];
  if (!found || found.IsNull()) fail(node_, key, "required but missing");
  return found;
}

void YamlMap::ignore(const std::string& key) { accept(key); }

void YamlMap::accept(const std::string& key) {
  read_keys_.push_back(key);
  if (accepted_log_) accepted_log_->push_back(field(key));
}

double YamlMap::number_at(const YAML::Node& node, const std::string& key, Range range) const {
  double result = 0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, result) || !std::isfinite(result)) {
    fail(node, key, "expected a finite number, got " + got_text(node));
  }
  if (!(result >= range.low && result <= range.high)) {
    fail(node, key, "must be in " + range_text(range.low, range.high) + ", got " + number_text(result));
  }
  return result;
}

long long YamlMap::integer_at(const YAML::Node& node, const std::string& key, long long low, long long high) const {
  long long result = 0;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, result)) {
    fail(node, key, "expected an integer, got " + got_text(node));
  }
  if (result < low || result > high) {
    fail(node, key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " + std::to_string(result));
  }
  return result;
}

double YamlMap::number(const std::string& key, Range range) { return number_at(value(key), key, range); }

double YamlMap::number(const std::string& key, Range range, double fallback) {
  return optional_number(key, range).value_or(fallback);
}

std::optional<double> YamlMap::optional_number(const std::string& key, Range range) {
  if (!has(key)) {
    accept(key);
    return std::nullopt;
  }
  return number(key, range);
}

long long YamlMap::integer(const std::string& key, long long low, long long high) {
  return integer_at(value(key), key, low, high);
}

long long YamlMap::integer(const std::string& key, long long low, long long high, long long fallback) {
  if (!has(key)) {
    accept(key);
    return fallback;
  }
  return integer(key, low, high);
}

std::string YamlMap::text(const std::string& key) {
  const YAML::Node node = value(key);
  if (!node.IsScalar()) fail(node, key, "expected a single value");
  return node.Scalar();
}

bool YamlMap::boolean(const std::string& key) {
  const std::string value = text(key);
  if (value == "true") return true;
  if (value == "false") return false;
  fail_key(key, "expected true or false, got '" + value + "'");
}

bool YamlMap::boolean(const std::string& key, bool fallback) {
  if (!has(key)) {
    accept(key);
    return fallback;
  }
  return boolean(key);
}

std::filesystem::path YamlMap::path(const std::string& key) {
  const std::string value = text(key);
  if (value.empty()) fail_key(key, "expected a file name, got an empty one");
  const std::filesystem::path path(value);
  return path.is_absolute() ? path : std::filesystem::path(file_).parent_path() / path;
}

Dof YamlMap::dof(const std::string& key) {
  const YAML::Node node = value(key);
  long long dof = 0;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, dof) || (dof != 3 && dof != 4 && dof != 6)) {
    fail(node, key, "must be 3, 4 or 6, got " + (node.IsScalar() ? node.Scalar() : "a list or mapping"));
  }
  return static_cast<Dof>(dof);
}

std::vector<double> YamlMap::numbers(const std::string& key, std::size_t count, Range range) {
  const YAML::Node node = value(key);
  if (!node.IsSequence() || node.size() != count) {
    fail(node, key, "expected a list of " + std::to_string(count) + " numbers");
  }
  std::vector<double> result;
  for (const YAML::Node& item : node) result.push_back(number_at(item, key, range));
  return result;
}

Eigen::Vector2d YamlMap::vector2(const std::string& key, Range range) {
  const std::vector<double> v = numbers(key, 2, range);
  return {v[0], v[1]};
}

Eigen::Vector3d YamlMap::vector3(const std::string& key, Range range) {
  const std::vector<double> v = numbers(key, 3, range);
  return {v[0], v[1], v[2]};
}

YamlMap YamlMap::map(const std::string& key) {
  YamlMap child(value(key), file_, field(key));
  child.accepted_log_ = accepted_log_;
  return child;
}

std::optional<YamlMap> YamlMap::optional_map(const std::string& key) {
  if (!has(key)) {
    accept(key);
    return std::nullopt;
  }
  return map(key);
}

std::vector<YAML::Node> YamlMap::items(const std::string& key) {
  accept(key);
  const YAML::Node node = std::as_const(node_)[key];
  if (!node || node.IsNull()) return {};
  if (!node.IsSequence()) fail(node, key, "expected a list");
  return {node.begin(), node.end()};
}

std::vector<std::vector<double>> YamlMap::points(const std::string& key, std::size_t dimensions, Range range) {
  std::vector<std::vector<double>> result;
  const std::string shape = dimensions == 2 ? "[x, y]" : "[x, y, z]";
  for (const YAML::Node& node : items(key)) {
    if (!node.IsSequence() || node.size() != dimensions) fail(node, key, "expected a list of " + shape + " points");
    std::vector<double>& point = result.emplace_back();
    for (const YAML::Node& coordinate : node) point.push_back(number_at(coordinate, key, range));
  }
  return result;
}

std::vector<long long> YamlMap::integers(const std::string& key, long long low, long long high) {
  std::vector<long long> result;
  for (const YAML::Node& node : items(key)) result.push_back(integer_at(node, key, low, high));
  return result;
}

void YamlMap::reject_unknown_keys() const {
  for (const auto& entry : node_) {
    const std::string& key = entry.first.Scalar();
    if (std::find(read_keys_.begin(), read_keys_.end(), key) == read_keys_.end()) {
      fail(entry.first, key, "unknown key");
    }
  }
}

}  // namespace irloc::io
