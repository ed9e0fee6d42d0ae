#include "hal/config/yaml_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <utility>

#include "hal/input_error.hpp"

namespace irloc::hal {
namespace {

int line_of(const YAML::Node& node) { return node.Mark().line + 1; }

}  // namespace

YAML::Node load_yaml_file(const std::filesystem::path& path) {
  std::ifstream stream(path);
  if (!stream) {
    throw InputError(path.string() + ": cannot open: " + std::strerror(errno));
  }
  try {
    YAML::Node root = YAML::Load(stream);
    if (!root.IsMap()) throw InputError(path.string() + ": expected a YAML mapping at the top level");
    return root;
  } catch (const YAML::ParserException& e) {
    throw InputError(path.string() + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
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
  const YAML::Node at = node_[key];
  fail(at ? at : node_, key, problem);
}

bool YamlMap::has(const std::string& key) const { return static_cast<bool>(node_[key]); }

YAML::Node YamlMap::value(const std::string& key) {
  read_keys_.push_back(key);
  YAML::Node found = std::as_const(node_)[key];
  if (!found || found.IsNull()) fail(node_, key, "required but missing");
  return found;
}

void YamlMap::ignore(const std::string& key) { read_keys_.push_back(key); }

double as_number(const YamlMap& owner, const YAML::Node& node, const std::string& field) {
  double result = 0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, result) || !std::isfinite(result)) {
    const std::string got = node.IsScalar() ? "'" + node.Scalar() + "'" : "a list or mapping";
    owner.fail(node, field, "expected a finite number, got " + got);
  }
  return result;
}

double YamlMap::number(const std::string& key) { return as_number(*this, value(key), key); }

std::optional<double> YamlMap::optional_number(const std::string& key) {
  if (!has(key)) {
    read_keys_.push_back(key);
    return std::nullopt;
  }
  return number(key);
}

long long YamlMap::integer(const std::string& key) {
  const YAML::Node node = value(key);
  long long result = 0;
  if (!node.IsScalar() || !YAML::convert<long long>::decode(node, result)) {
    const std::string got = node.IsScalar() ? "'" + node.Scalar() + "'" : "a list or mapping";
    fail(node, key, "expected an integer, got " + got);
  }
  return result;
}

std::string YamlMap::text(const std::string& key) {
  const YAML::Node node = value(key);
  if (!node.IsScalar()) fail(node, key, "expected a single value");
  return node.Scalar();
}

std::vector<double> YamlMap::numbers(const std::string& key, std::size_t count) {
  const YAML::Node node = value(key);
  if (!node.IsSequence() || node.size() != count) {
    fail(node, key, "expected a list of " + std::to_string(count) + " numbers");
  }
  std::vector<double> result;
  for (const YAML::Node& item : node) result.push_back(as_number(*this, item, key));
  return result;
}

YamlMap YamlMap::map(const std::string& key) { return YamlMap(value(key), file_, field(key)); }

std::vector<YAML::Node> YamlMap::items(const std::string& key) {
  read_keys_.push_back(key);
  const YAML::Node node = std::as_const(node_)[key];
  if (!node || node.IsNull()) return {};
  if (!node.IsSequence()) fail(node, key, "expected a list");
  return {node.begin(), node.end()};
}

void YamlMap::reject_unknown_keys() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.as<std::string>();
    if (std::find(read_keys_.begin(), read_keys_.end(), key) == read_keys_.end()) {
      fail(entry.first, key, "unknown key");
    }
  }
}

}  // namespace irloc::hal
