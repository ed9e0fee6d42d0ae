#include "hal/linux/gpiod_strobe.hpp"

#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "io/input_error.hpp"

namespace irloc::hal {
namespace {

[[noreturn]] void fail(const GpioLine& where, const std::string& problem) {
  throw io::InputError("strobe: " + where.chip + ": " + problem);
}

std::string system_error(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

#ifndef IRLOC_GPIOD_V2

struct GpiodStrobe::Handles {
  gpiod_chip* chip = nullptr;
  gpiod_line* line = nullptr;
};

GpiodStrobe::GpiodStrobe(const GpioLine& line) : where_(line), handles_(new Handles) {
  // gpiod_chip_open_lookup takes a name, a path, a number or a label.
  handles_->chip = gpiod_chip_open_lookup(line.chip.c_str());
  if (!handles_->chip) {
    delete handles_;
    fail(line, system_error("cannot open GPIO chip"));
  }
  handles_->line = gpiod_chip_get_line(handles_->chip, line.line);
  if (!handles_->line) {
    const std::string problem = system_error("no line " + std::to_string(line.line) + " (the chip has " +
                                             std::to_string(gpiod_chip_num_lines(handles_->chip)) + ")");
    gpiod_chip_close(handles_->chip);
    delete handles_;
    fail(line, problem);
  }
  const int flags = line.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (gpiod_line_request_output_flags(handles_->line, "irlocd", flags, 0) != 0) {
    const std::string problem = system_error("cannot claim line " + std::to_string(line.line) + " as an output");
    gpiod_chip_close(handles_->chip);
    delete handles_;
    fail(line, problem);
  }
}

GpiodStrobe::~GpiodStrobe() {
  gpiod_line_set_value(handles_->line, 0);
  gpiod_line_release(handles_->line);
  gpiod_chip_close(handles_->chip);
  delete handles_;
}

void GpiodStrobe::set_led(bool on) {
  if (gpiod_line_set_value(handles_->line, on ? 1 : 0) != 0) fail(where_, system_error("cannot set line"));
}

#else  // libgpiod v2

namespace {

// v2 opens chips by path only: a bare name is looked up under /dev, then by label.
std::string chip_path(const GpioLine& line) {
  if (line.chip.starts_with("/")) return line.chip;
  const std::filesystem::path by_name = std::filesystem::path("/dev") / line.chip;
  if (std::filesystem::exists(by_name)) return by_name.string();
  std::error_code ignored;
  for (const auto& entry : std::filesystem::directory_iterator("/dev", ignored)) {
    if (!entry.path().filename().string().starts_with("gpiochip")) continue;
    gpiod_chip* chip = gpiod_chip_open(entry.path().c_str());
    if (!chip) continue;
    gpiod_chip_info* info = gpiod_chip_get_info(chip);
    const bool match = info && line.chip == gpiod_chip_info_get_label(info);
    if (info) gpiod_chip_info_free(info);
    gpiod_chip_close(chip);
    if (match) return entry.path().string();
  }
  return by_name.string();
}

}  // namespace

struct GpiodStrobe::Handles {
  gpiod_chip* chip = nullptr;
  gpiod_line_request* request = nullptr;
};

GpiodStrobe::GpiodStrobe(const GpioLine& line) : where_(line), handles_(new Handles) {
  handles_->chip = gpiod_chip_open(chip_path(line).c_str());
  if (!handles_->chip) {
    delete handles_;
    fail(line, system_error("cannot open GPIO chip"));
  }
  gpiod_line_settings* settings = gpiod_line_settings_new();
  gpiod_line_config* config = gpiod_line_config_new();
  gpiod_request_config* request_config = gpiod_request_config_new();
  if (settings && config && request_config) {
    gpiod_line_settings_set_direction(settings, GPIOD_LINE_DIRECTION_OUTPUT);
    gpiod_line_settings_set_output_value(settings, GPIOD_LINE_VALUE_INACTIVE);
    gpiod_line_settings_set_active_low(settings, line.active_low);
    const unsigned int offset = line.line;
    gpiod_request_config_set_consumer(request_config, "irlocd");
    if (gpiod_line_config_add_line_settings(config, &offset, 1, settings) == 0) {
      handles_->request = gpiod_chip_request_lines(handles_->chip, request_config, config);
    }
  }
  const std::string problem = system_error("cannot claim line " + std::to_string(line.line) + " as an output");
  if (request_config) gpiod_request_config_free(request_config);
  if (config) gpiod_line_config_free(config);
  if (settings) gpiod_line_settings_free(settings);
  if (!handles_->request) {
    gpiod_chip_close(handles_->chip);
    delete handles_;
    fail(line, problem);
  }
}

GpiodStrobe::~GpiodStrobe() {
  gpiod_line_request_set_value(handles_->request, where_.line, GPIOD_LINE_VALUE_INACTIVE);
  gpiod_line_request_release(handles_->request);
  gpiod_chip_close(handles_->chip);
  delete handles_;
}

void GpiodStrobe::set_led(bool on) {
  const gpiod_line_value value = on ? GPIOD_LINE_VALUE_ACTIVE : GPIOD_LINE_VALUE_INACTIVE;
  if (gpiod_line_request_set_value(handles_->request, where_.line, value) != 0) {
    fail(where_, system_error("cannot set line"));
  }
}

#endif

}  // namespace irloc::hal
