#pragma once
// A config section declared once: a table of settings, each its key, the struct member it sets,
// its range, unit and one line of doc. The member's default is the struct's own initializer
// (AprilTag-style: one struct, its defaults in one place). The reader (read_settings), the
// commented config of `irlocd --print-config` and docs/config.md are all made from the tables
// (config_reference.hpp).

#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <variant>

#include "io/config/yaml_reader.hpp"

namespace irloc::io {

template <typename Section>
struct Setting {
  const char* key;
  std::variant<double Section::*, int Section::*, std::uint32_t Section::*, std::uint16_t Section::*, bool Section::*>
      member;
  double low;   // the closed range of the value (unused for a boolean)
  double high;
  const char* unit;  // "" for a ratio, a count or a boolean
  const char* doc;   // one line: what it does
};

// Reads every setting of `table` that `section` gives into `values` (absent ones keep theirs);
// throws InputError "FILE:LINE: FIELD: PROBLEM" for a value of the wrong kind or out of range.
// Unknown keys are left to the caller's reject_unknown_keys().
template <typename Section>
void read_settings(YamlMap& section, std::span<const Setting<Section>> table, Section& values) {
  for (const Setting<Section>& setting : table) {
    std::visit(
        [&](auto member) {
          auto& value = values.*member;
          using Value = std::remove_reference_t<decltype(value)>;
          if constexpr (std::is_same_v<Value, double>) {
            value = section.number(setting.key, Range{setting.low, setting.high}, value);
          } else if constexpr (std::is_same_v<Value, bool>) {
            value = section.boolean(setting.key, value);
          } else {
            value = static_cast<Value>(section.integer(setting.key, static_cast<long long>(setting.low),
                                                       static_cast<long long>(setting.high), value));
          }
        },
        setting.member);
  }
}

// The YAML text of one setting's value in `values` ("0.25", "48", "true").
template <typename Section>
std::string setting_value_text(const Setting<Section>& setting, const Section& values) {
  return std::visit(
      [&](auto member) -> std::string {
        const auto& value = values.*member;
        using Value = std::remove_cvref_t<decltype(value)>;
        if constexpr (std::is_same_v<Value, double>) {
          return number_text(value);
        } else if constexpr (std::is_same_v<Value, bool>) {
          return value ? "true" : "false";
        } else {
          return std::to_string(value);
        }
      },
      setting.member);
}

// The comment of a setting: its doc, unit and range ("noise sigmas above the median; [1, 100]").
template <typename Section>
std::string setting_comment(const Setting<Section>& setting) {
  std::string comment = setting.doc;
  if (std::holds_alternative<bool Section::*>(setting.member)) return comment + "; true or false";
  comment += "; ";
  if (std::holds_alternative<double Section::*>(setting.member)) {
    comment += range_text(setting.low, setting.high);
  } else {  // as the reader's message prints an integer's range (appended: GCC 12's false -Wrestrict)
    comment += "[";
    comment += std::to_string(static_cast<long long>(setting.low));
    comment += ", ";
    comment += std::to_string(static_cast<long long>(setting.high));
    comment += "]";
  }
  if (*setting.unit != '\0') {
    comment += " ";
    comment += setting.unit;
  }
  return comment;
}

}  // namespace irloc::io
