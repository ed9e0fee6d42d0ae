#pragma once
// The LED ring's driver line on a GPIO chip through libgpiod: the v1 API of Debian 12 (1.6), or
// the v2 API when the build finds libgpiod >= 2 (IRLOC_GPIOD_V2).

#include <string>

#include "hal/strobe.hpp"

namespace irloc::hal {

struct GpioLine {
  std::string chip;        // "gpiochip0", "/dev/gpiochip0" or the chip's label ("pinctrl-rp1")
  unsigned int line = 0;   // line offset on that chip (on a Raspberry Pi, the BCM GPIO number)
  bool active_low = false; // true when the driver lights the LEDs at a low level
};

class GpiodStrobe final : public Strobe {
 public:
  // Claims the line as an output, LEDs off, consumer "irlocd". Throws io::InputError
  // "strobe: CHIP: problem" for a missing chip, a line beyond the chip, or a line in use.
  explicit GpiodStrobe(const GpioLine& line);
  ~GpiodStrobe() override;
  GpiodStrobe(const GpiodStrobe&) = delete;
  GpiodStrobe& operator=(const GpiodStrobe&) = delete;

  void set_led(bool on) override;

 private:
  struct Handles;
  GpioLine where_;
  Handles* handles_;  // libgpiod objects; owned, freed in the destructor
};

}  // namespace irloc::hal
