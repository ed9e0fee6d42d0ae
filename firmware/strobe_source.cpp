#include "firmware/strobe_source.hpp"

#include "firmware/camera_source.hpp"
#include "io/input_error.hpp"
#include "hal/linux/gpiod_strobe.hpp"

namespace irloc::firmware {

std::unique_ptr<hal::Strobe> open_strobe(const std::string& camera_spec, const std::optional<io::BoardStrobe>& board_strobe) {
  if (!is_live_camera(camera_spec) || camera_drives_its_leds(camera_spec)) return nullptr;
  if (!board_strobe) {
    throw io::InputError("--camera " + camera_spec + ": a live camera needs the LED strobe of a board file (--board)");
  }
  return std::make_unique<hal::GpiodStrobe>(hal::GpioLine{board_strobe->chip, board_strobe->line, board_strobe->active_low});
}

}  // namespace irloc::firmware
