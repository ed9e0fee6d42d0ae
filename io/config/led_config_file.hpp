#pragma once
// The optional `led:` section of the config YAML: the LED landmark source's tunables
// (algo/markers/led/led_config.hpp, docs/led_landmarks.md). Every key is optional; an unknown
// key or a value out of range is an InputError naming the file, line and field.

#include <span>

#include "algo/markers/led/led_config.hpp"
#include "io/config/setting_table.hpp"
#include "io/config/yaml_reader.hpp"

namespace irloc::io {

std::span<const Setting<led::LedSourceConfig>> led_settings();

led::LedSourceConfig read_led_config(YamlMap& section);

}  // namespace irloc::io
